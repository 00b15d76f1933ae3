"""Bad input raises ValueError with the command line's message: every scene of scenes/bad/
(file, line and field), overrides and limits (named by their keyword where the command line
names its flag), damaged data files, shade settings, geodesic and connect arguments."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import godel
from conftest import REPO, cli_error

BAD_SCENES = sorted((REPO / "scenes" / "bad").glob("*.toml"))


def keyword_of(message: str, flag: str, keyword: str) -> str:
    """The CLI's message with its flag named as the Python keyword."""
    assert message.startswith(flag + ": "), message
    return keyword + message[len(flag) :]


def test_there_are_bad_scenes():
    assert len(BAD_SCENES) >= 30


@pytest.mark.parametrize("scene", BAD_SCENES, ids=lambda p: p.name)
def test_bad_scenes_raise_the_cli_message(scene: Path, out: Path):
    relative = str(scene.relative_to(REPO))
    expected = cli_error("render", relative, "-o", str(out))
    with pytest.raises(ValueError) as raised:
        godel.render(relative, progress=False)
    assert str(raised.value) == expected
    assert relative in str(raised.value)


@pytest.mark.parametrize(
    "keyword,value,flag",
    [
        ("width", 0, "--width"),
        ("height", -3, "--height"),
        ("samples", 3, "--samples"),
        ("samples", 1024, "--samples"),
        ("method", "fast", "--method"),
        ("max_past", -1.0, "--max-past"),
        ("max_past", math.nan, "--max-past"),
        ("threads", 0, "--threads"),
        ("threads", 100_000, "--threads"),
    ],
)
def test_bad_overrides_are_named_by_their_keyword(keyword, value, flag, out):
    expected = cli_error("render", flag, str(value).lower(), "-o", str(out))
    with pytest.raises(ValueError) as raised:
        godel.render(progress=False, **{keyword: value})
    assert str(raised.value) == keyword_of(expected, flag, keyword)


def test_a_bad_scene_text_is_located_in_the_text():
    with pytest.raises(ValueError) as raised:
        godel.render('name = "x"\n[camera]\nwidth = -1\n', progress=False)
    message = str(raised.value)
    assert message.startswith("<scene text>:3:9: camera.width: "), message


def test_damaged_and_missing_data_files(out):
    not_exr = out / "not.exr"
    not_exr.write_text("hello")
    expected = cli_error("shade", str(not_exr), "-o", str(out / "x.png"))
    with pytest.raises(ValueError) as raised:
        godel.read(not_exr)
    assert str(raised.value) == expected
    missing = out / "missing.exr"
    expected = cli_error("shade", str(missing), "-o", str(out / "x.png"))
    with pytest.raises(FileNotFoundError) as raised:
        godel.read(missing)
    assert str(raised.value) == expected
    assert not (out / "x.png").exists()


def test_bad_shade_settings_name_the_field():
    image = godel.render(width=44, height=5, progress=False)
    cases = [
        (dict(objects={"moon": {"temperature": 4000}}), "objects.moon"),
        (dict(exposure="bright"), "exposure"),
        (dict(time={"t0": -6, "dt": 2, "colour": 1}), "time"),
        (dict(objects={"earth": {"temperature": -5}}), "objects.earth.temperature"),
    ]
    for settings, field in cases:
        with pytest.raises(ValueError) as raised:
            image.rgb(("frequency", "time"), **settings)
        assert str(raised.value).startswith(f"shade settings: {field}"), str(raised.value)
    with pytest.raises(ValueError) as raised:
        image.rgb(("texture", "sparkle"))
    assert "sparkle" in str(raised.value)
    with pytest.raises(ValueError, match="^the light shader needs light channels"):
        image.rgb(("light",))  # the reference scene has no lights
    with pytest.raises(ValueError, match="^ev: has no effect on a linear picture"):
        image.hdr(ev=1)


GEODESIC_CASES = [
    # (Python keywords, CLI flags, flag, keyword)
    (dict(speed=1.5), ["--speed", "1.5"], "--speed", "speed"),
    (dict(direction=(0, 0, 0)), ["--dir", "0,0,0"], "--dir", "direction"),
    (dict(samples=1), ["--samples", "1"], "--samples", "samples"),
    (dict(max_past=-2.0), ["--until-time", "-2"], "--until-time", "max_past"),
    (dict(a=0.0), ["--a", "0"], "--a", "a"),
]


@pytest.mark.parametrize("kwargs,flags,flag,keyword", GEODESIC_CASES)
def test_bad_geodesic_arguments(kwargs, flags, flag, keyword):
    args = {"--at": "0,0,0,0", "--dir": "1,0,0"}
    for name, value in zip(flags[::2], flags[1::2]):
        args[name] = value
    cli = ["geodesic", "--past"] + [x for kv in args.items() for x in kv]
    expected = cli_error(*cli)
    with pytest.raises(ValueError) as raised:
        godel.geodesic(**kwargs)
    assert str(raised.value) == keyword_of(expected, flag, keyword)


def test_bad_geodesic_and_connect_values():
    with pytest.raises(ValueError, match='^method: must be "exact" or "numeric"'):
        godel.geodesic(method="euler")
    with pytest.raises(ValueError, match="^position: "):
        godel.geodesic(position=(math.inf, 0, 0))
    with pytest.raises(ValueError, match="^position: expected 3 numbers"):
        godel.geodesic(position=(1, 2))
    with pytest.raises(ValueError, match="^source: expected the position"):
        godel.connect(source=(0, 1, 0, 0), target=(0, 0, 0, 0))
    expected = cli_error("connect", "--from", "0,0,0,0", "--to-source", "1,0,0",
                         "--windings", "1001")
    with pytest.raises(ValueError) as raised:
        godel.connect(source=(1, 0, 0), target=(0, 0, 0, 0), windings=1001)
    assert str(raised.value) == keyword_of(expected, "--windings", "windings")
    with pytest.raises(ValueError, match="^a: must be positive"):
        godel.connect(source=(1, 0, 0), target=(0, 0, 0, 0), a=-1)


def test_the_scale_and_coordinates_have_the_ranges_of_scenes():
    # As `godel geodesic --a 1e-300` and `--at 1e300,…`: the ranges scenes allow.
    expected = cli_error("geodesic", "--at", "0,0,0,0", "--dir", "1,0,0", "--a", "1e-300")
    with pytest.raises(ValueError) as raised:
        godel.geodesic(a=1e-300)
    assert str(raised.value) == keyword_of(expected, "--a", "a")
    expected = cli_error("geodesic", "--at", "1e300,0,0,0", "--dir", "1,0,0")
    with pytest.raises(ValueError) as raised:
        godel.geodesic(time=1e300)
    assert str(raised.value) == keyword_of(expected, "--at", "time")
    with pytest.raises(ValueError, match=r"^position: z = 3e6 is beyond ±1e6"):
        godel.geodesic(position=(0, 0, 3e6))
    with pytest.raises(ValueError, match=r"^target: t = -2e6 is beyond ±1e6"):
        godel.connect(source=(0.5, 0, 0), target=(-2e6, 0, 0, 0))
    with pytest.raises(ValueError, match=r"^a: 1e300 is outside"):
        godel.connect(source=(0.5, 0, 0), target=(0, 0, 0, 0), a=1e300)
    # At the bounds themselves all is well.
    assert godel.geodesic(time=1e6, samples=2)["t"][0] == 1e6
    assert godel.connect(source=(0.5, 0, 0), target=(-1e6, 0, 0, 0))


def test_a_render_beyond_the_memory_budget_is_refused(monkeypatch, out):
    monkeypatch.setenv("GODEL_MEMORY_BUDGET", "1000")
    expected = cli_error("render", "--width", "44", "--height", "5", "-o", str(out))
    with pytest.raises(ValueError) as raised:
        godel.render(width=44, height=5, progress=False)
    assert str(raised.value) == expected
    assert "needs about" in expected and expected.startswith("built-in scene: camera: ")


def test_a_memory_budget_that_is_not_one_is_named(monkeypatch, out):
    # Issue 36: ignored silently before; now refused as the command line refuses it.
    monkeypatch.setenv("GODEL_MEMORY_BUDGET", "abc")
    expected = cli_error("render", "--width", "44", "--height", "5", "-o", str(out))
    assert expected == 'GODEL_MEMORY_BUDGET: must be a number of bytes from 0 to 1e18 ' \
        '(e.g. 8e9), got "abc"'
    with pytest.raises(ValueError) as raised:
        godel.render(width=44, height=5, progress=False)
    assert str(raised.value) == expected


def test_connect_refuses_an_event_on_the_source_axis():
    # Issue 36: the source at the event gave a ray of travel time 0 in an arbitrary direction.
    for target, why in [((2.0, 0.7, 0.1, 0.3), "the source is at the event's place"),
                        ((2.0, 0.7, 0.1, 1.3), "the event is on the source's axis")]:
        with pytest.raises(ValueError, match=f"^target: {why}"):
            godel.connect(source=(0.7, 0.1, 0.3), target=target)
    assert godel.connect(source=(0.7, 0.1, 0.3), target=(2.0, 0.75, 0.1, 0.3))


# --- Files (issue 36): a missing file, a folder or an empty path given where a file belongs.


def test_a_missing_scene_file_is_file_not_found_with_the_cli_message(out):
    missing = out / "missing.toml"
    expected = cli_error("render", str(missing), "-o", str(out / "pics"))
    for overrides in ({}, {"width": 44}):
        with pytest.raises(FileNotFoundError) as raised:
            godel.render(missing, progress=False, **overrides)
        assert str(raised.value) == expected


def test_a_folder_where_a_file_belongs_is_called_a_folder(out):
    image = godel.render(width=44, height=5, progress=False)
    named_exr = out / "pics.exr"
    named_exr.mkdir()
    to_write = "the name of the data file to write (.exr)"
    cases = [
        (lambda: godel.render(out, progress=False), out, "a scene file"),
        (lambda: godel.render(out, width=44, progress=False), out, "a scene file"),
        (lambda: godel.read(out), out, "a data file"),
        (lambda: godel.read(named_exr), named_exr, "a data file"),
        (lambda: image.save(out), out, to_write),
        (lambda: image.save(named_exr), named_exr, to_write),
    ]
    for call, folder, what in cases:
        with pytest.raises(IsADirectoryError) as raised:
            call()
        assert str(raised.value) == f"{folder}: is a folder, not {what}"
    # Nothing written, the folder left as it was.
    assert [p.name for p in out.iterdir()] == ["pics.exr"]
    assert not any(named_exr.iterdir())


def test_an_empty_path_names_its_argument():
    image = godel.render(width=44, height=5, progress=False)
    with pytest.raises(ValueError, match=r"^scene: an empty path, not a scene file$"):
        godel.render("", progress=False)
    with pytest.raises(ValueError, match=r"^path: an empty path, not a data file$"):
        godel.read("")
    with pytest.raises(ValueError, match=r"^path: an empty path, not the name of the data file"):
        image.save("")


def test_a_missing_texture_is_refused_as_part_of_its_input(out):
    # A file named inside the input is that input's mistake, as on the command line: the
    # scene's (scenes/bad/missing-texture-file.toml above) and the shade settings'.
    image = godel.render(width=44, height=5, progress=False)
    missing = out / "no-such-image.png"
    with pytest.raises(ValueError) as raised:
        image.rgb(objects={"earth": {"texture": {"kind": "image", "path": str(missing)}}})
    assert str(raised.value).startswith(f"image texture {missing}: "), str(raised.value)
