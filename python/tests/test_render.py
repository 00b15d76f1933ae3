"""godel.render and godel.read against the command line: the same records, bit for bit,
read from the CLI's data file by the OpenEXR module (not godel's reader); the same pictures
as ``godel shade``; a saved image is the CLI's file, byte for byte."""

from __future__ import annotations

import filecmp
from pathlib import Path

import numpy as np
import pytest

import godel
from conftest import REPO, read_exr, read_png, run_cli, same_bits

#: Small renders: (scene path or None, overrides as keyword arguments).
CASES = [
    (None, dict(width=176, height=20)),  # the reference scene, 2×2 samples per pixel
    ("scenes/lit-shadow.toml", dict(width=96, height=12, method="exact", max_past=12.0)),
    ("scenes/static-sphere.toml", dict(width=72, height=12, samples=4, method="numeric")),
    # The reference scene in a member of the Gödel-type family (its a dropped).
    (None, dict(width=88, height=10, samples=1, metric="godel-type", m2=0.5, omega=0.7)),
    # A lit scene in a member: its light channel too.
    ("scenes/lit-godel-type.toml", dict(width=96, height=12)),
]


def cli_flags(overrides: dict) -> list:
    flags = []
    for key, value in overrides.items():
        flags += [f"--{key.replace('_', '-')}", str(value)]
    return flags


def render_cli(scene, overrides: dict, out: Path, *extra: str) -> Path:
    """The data file ``godel render`` writes (into ``out``, under the scene's name)."""
    args = ["render", *([scene] if scene else []), *cli_flags(overrides), "-o", str(out)]
    run_cli(*args, "--quiet", *extra)
    (exr,) = out.glob("*.exr")
    return exr


def assert_same_records(image: godel.Image, file: dict) -> None:
    """The image's channels are the file's, bit for bit, names and types as documented."""
    assert set(image.channels) == set(file)
    for name, values in image.channels.items():
        stored = file[name]
        assert values.shape == stored.shape, name
        if name == "object":
            assert values.dtype == np.int32
            assert same_bits(values.astype(np.float32), stored)
        elif name == "status":
            assert values.dtype == np.uint8
            assert np.array_equal(values, stored)
        else:
            assert values.dtype == np.float32, name
            assert same_bits(values, stored), name


@pytest.mark.parametrize("scene,overrides", CASES)
def test_render_equals_the_cli_data_file_bit_for_bit(scene, overrides, out):
    path = str(REPO / scene) if scene else None
    image = godel.render(path, progress=False, **overrides)
    exr = render_cli(path, overrides, out)
    assert_same_records(image, read_exr(exr))
    # Written back, it is the very file the command line wrote.
    image.save(out / "saved.exr")
    assert filecmp.cmp(out / "saved.exr", exr, shallow=False)
    # And read, the CLI's file gives the same channels again.
    assert_same_records(godel.read(exr), read_exr(exr))


def test_records_do_not_depend_on_the_thread_count(out):
    one = godel.render(None, width=88, height=10, threads=1, progress=False)
    exr = render_cli(None, dict(width=88, height=10), out, "--threads", "2")
    assert_same_records(one, read_exr(exr))


def test_channels_follow_the_data_file_conventions():
    image = godel.render(None, width=176, height=20, progress=False)
    assert image.samples == 2 and image.shape == (40, 352)
    assert image.header["objects"] == ["earth"] and image.header["method"] == "numeric"
    status, g = image["status"], image["g"]
    hit = status == 0
    assert hit.any() and (~hit).any(), "the reference scene has hits and misses"
    # No value where there is none; where the ray hit, every physical channel is set.
    for name in ("u", "v", "g", "t_emit", "x", "y", "z", "lambda", "cos_i", "dir_x"):
        assert np.isnan(image[name][~hit]).all(), name
        assert np.isfinite(image[name][hit]).all(), name
    assert (image["object"][hit] == 0).all() and (image["object"][~hit] == -1).all()
    # Every traced ray has a unit camera direction; light left the ball in the past.
    view = np.stack([image[f"view_{c}"] for c in "xyz"], axis=-1)
    assert np.allclose(np.linalg.norm(view, axis=-1), 1.0, atol=1e-6)
    assert (image["t_emit"][hit] < 0).all() and (g[hit] > 0).all()
    # The polarization channels: a unit vector orthogonal to the emission direction where
    # the ray hit, NaN elsewhere (issue 25).
    pol = np.stack([image[f"pol_{c}"] for c in "xyz"], axis=-1)
    dirs = np.stack([image[f"dir_{c}"] for c in "xyz"], axis=-1)
    assert np.isnan(pol[~hit]).all()
    assert np.allclose(np.linalg.norm(pol[hit], axis=-1), 1.0, atol=1e-6)
    assert np.allclose(np.sum(pol[hit] * dirs[hit], axis=-1), 0.0, atol=1e-6)
    assert "width = 176" in image.scene and "height = 20" in image.scene
    assert "0 failed" in image.summary


def test_scene_text_renders_as_its_file():
    path = REPO / "scenes" / "static-sphere.toml"
    from_file = godel.render(path, width=48, height=8, progress=False)
    from_text = godel.render(path.read_text(), width=48, height=8, progress=False)
    for name, values in from_file.channels.items():
        assert same_bits(values, from_text[name]), name


@pytest.mark.parametrize(
    "shaders,settings,flags",
    [
        (("texture",), {}, []),
        (("frequency",), {}, ["--shader", "frequency"]),
        (("texture", "frequency"), {"ev": -1, "grid": True},
         ["--shader", "texture,frequency", "--ev", "-1", "--grid"]),
        (("time",), {"time": {"mode": "travel", "travel_min": 0, "travel_max": 12}},
         ["--shader", "time", "--travel", "0,12"]),
        (("frequency",), {"objects": {"earth": {"temperature": 4000}}, "brightness": "physical",
                          "exposure": 0.5},
         ["--shader", "frequency", "--temperature", "earth=4000", "--exposure", "0.5"]),
    ],
)
def test_pictures_equal_godel_shade(shaders, settings, flags, out):
    exr = render_cli(None, dict(width=176, height=20), out)
    image = godel.read(exr)
    run_cli("shade", str(exr), *flags, "-o", str(out / "shade.png"))
    rgb = image.rgb(shaders, **settings)
    assert rgb.dtype == np.uint8 and rgb.shape == (20, 176, 3)
    assert np.array_equal(rgb, read_png(out / "shade.png"))
    display_only = ("--ev", "--grid")
    linear_flags = [f for i, f in enumerate(flags)
                    if f not in display_only and (i == 0 or flags[i - 1] not in display_only)]
    run_cli("shade", str(exr), *linear_flags, "-o", str(out / "shade.exr"))
    linear = {k: v for k, v in settings.items() if k not in ("ev", "grid")}
    hdr = image.hdr(shaders, **linear)
    stored = read_exr(out / "shade.exr")
    assert hdr.dtype == np.float32 and hdr.shape == (20, 176, 3)
    for k, channel in enumerate("RGB"):
        assert same_bits(hdr[..., k], stored[channel]), channel


def test_render_without_a_scene_is_the_builtin_reference():
    image = godel.render(width=44, height=5, progress=False)
    assert image.header["scene_name"] == "reference"
    reference = godel.render(REPO / "scenes" / "reference.toml", width=44, height=5,
                             progress=False)
    for name, values in image.channels.items():
        assert same_bits(values, reference[name]), name


def test_save_takes_a_data_file_name_and_leaves_nothing_when_it_fails(out):
    # Issue 36: save("x.png") wrote an EXR into x.png. The data file's name ends in .exr, in
    # any case, as the command line's -o takes it (and writes it under the name given).
    image = godel.render(width=44, height=5, progress=False)
    mine = out / "mine.png"
    mine.write_bytes(b"a picture of mine")
    for name in ("x.png", "mine.png", "x", "x.exr.part", "x.tiff"):
        with pytest.raises(ValueError) as raised:
            image.save(out / name)
        assert str(raised.value) == (
            f"path: must name the data file to write (.exr), got {out / name}; "
            "rgb() and hdr() give pictures"
        )
    with pytest.raises(FileNotFoundError):
        image.save(out / "no-such-folder" / "x.exr")
    assert [p.name for p in out.iterdir()] == ["mine.png"]  # no temporary either
    assert mine.read_bytes() == b"a picture of mine"
    for name in ("x.exr", "y.EXR"):
        image.save(out / name)
        assert same_bits(godel.read(out / name)["g"], image["g"])
    assert filecmp.cmp(out / "x.exr", out / "y.EXR", shallow=False)
    assert sorted(p.name for p in out.iterdir()) == ["mine.png", "x.exr", "y.EXR"]
