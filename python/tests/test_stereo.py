"""godel.render of a stereo scene (``[camera] stereo``): both eyes traced, each an ordinary
image equal to the data file ``godel render`` writes for it (bit for bit, read by the
OpenEXR module, and saved byte for byte); eyes 0 apart see exactly what one observer sees;
the pair's picture is ``godel shade``'s of the pair; and what belongs to one eye is refused
on the pair with a message saying to choose one."""

from __future__ import annotations

import filecmp
import re
from pathlib import Path

import numpy as np
import pytest

import godel
from conftest import REPO, read_exr, read_png, run_cli, same_bits
from test_render import assert_same_records

#: The reference scene with eyes 0.1a apart (an anaglyph), rendered small.
SCENE = (REPO / "scenes" / "reference-anaglyph.toml").read_text()
NAME = "reference-anaglyph"
SMALL = dict(width=88, height=10, samples=1)


def with_stereo(stereo: str | None) -> str:
    """The scene with its ``stereo = …`` line replaced by ``stereo`` (None: removed)."""
    line = "" if stereo is None else f"stereo = {stereo}\n"
    text, n = re.subn(r"^stereo = .*\n", line, SCENE, flags=re.M)
    assert n == 1
    return text


def assert_same_channels(a: godel.Image, b: godel.Image) -> None:
    assert set(a.channels) == set(b.channels)
    for name, values in a.channels.items():
        if values.dtype == np.float32:
            assert same_bits(values, b[name]), name
        else:
            assert np.array_equal(values, b[name]), name


def test_eyes_zero_apart_see_what_one_observer_sees():
    mono = godel.render(with_stereo(None), progress=False, **SMALL)
    pair = godel.render(with_stereo('{ separation = 0.0, layout = "side-by-side" }'),
                        progress=False, **SMALL)
    assert mono.stereo is None
    assert pair.stereo == godel.Stereo(0.0, "side-by-side", None)
    for eye in ("left", "right"):
        image = pair.eye(eye)
        assert type(image) is godel.Image and image.stereo is None
        assert image.header["scene_name"] == f"{NAME}.{eye}"
        assert_same_channels(image, mono)
        assert np.array_equal(image["g"], mono["g"], equal_nan=True)


def test_eyes_apart_see_different_pictures():
    pair = godel.render(SCENE, progress=False, **SMALL)
    assert pair.stereo == godel.Stereo(0.1, "anaglyph", None)
    left, right = pair.eye("left"), pair.eye("right")
    assert left.shape == right.shape == pair.shape == (10, 88) and pair.samples == 1
    hit = (left["status"] == 0) & (right["status"] == 0)
    assert hit.any()
    assert not np.array_equal(left["g"], right["g"], equal_nan=True)
    assert not np.array_equal(left["t_emit"], right["t_emit"], equal_nan=True)
    # Parallel eyes: each pixel looks the same way in its eye's frame.
    assert same_bits(left["view_x"], right["view_x"])
    # The pair's scene is the scene as rendered; each eye holds its own.
    assert "separation = 0.1" in pair.scene and "width = 88" in pair.scene
    assert 'eye = "left"' in left.scene and 'eye = "right"' in right.scene
    assert pair.summary.startswith("left eye: ") and "\nright eye: " in pair.summary


def test_both_eyes_are_traced_and_counted():
    job = godel._godel.RenderJob(None, SCENE, 88, 10, 1, None, None, 1)
    assert job.wait(None)
    assert job.total == job.done == 2 * 88 * 10
    assert job.stereo == (0.1, "anaglyph", None)
    assert "width = 88\n" in job.scene and "separation = 0.1" in job.scene
    assert len(job.result()) == 2


def test_eyes_equal_the_cli_data_files_and_the_pair_picture_godel_shade(out):
    scene = out / "pair.toml"
    scene.write_text(SCENE)
    pair = godel.render(scene, progress=False, **SMALL)
    files = out / "cli"
    run_cli("render", str(scene), "--width", "88", "--height", "10", "--samples", "1",
            "-o", str(files), "--quiet")
    for eye in ("left", "right"):
        exr = files / f"{NAME}.{eye}.exr"
        assert_same_records(pair.eye(eye), read_exr(exr))
        pair.eye(eye).save(out / f"saved.{eye}.exr")
        assert filecmp.cmp(out / f"saved.{eye}.exr", exr, shallow=False)
    # The pair's picture is godel shade's of the left eye's file (both eyes, anaglyph).
    run_cli("shade", str(files / f"{NAME}.left.exr"), "--shader", "texture,frequency",
            "-o", str(out / "shade.png"))
    rgb = pair.rgb(("texture", "frequency"))
    assert rgb.dtype == np.uint8 and rgb.shape == (10, 88, 3)
    assert np.array_equal(rgb, read_png(out / "shade.png"))


@pytest.mark.parametrize("layout", ["side-by-side", "over-under"])
def test_the_pair_picture_holds_each_eye_in_its_layout(layout):
    stereo = f'{{ separation = 0.1, layout = "{layout}", convergence = 2.0 }}'
    pair = godel.render(with_stereo(stereo), progress=False, **SMALL)
    assert pair.stereo == godel.Stereo(0.1, layout, 2.0)
    left, right = pair.eye("left").rgb(), pair.eye("right").rgb()
    both = pair.rgb()
    if layout == "side-by-side":
        assert both.shape == (10, 176, 3)
        halves = both[:, :88], both[:, 88:]
    else:
        assert both.shape == (20, 88, 3)
        halves = both[:10], both[10:]
    assert np.array_equal(halves[0], left) and np.array_equal(halves[1], right)
    assert not np.array_equal(left, right)


def test_one_eye_file_reads_as_one_image(out):
    scene = out / "pair.toml"
    scene.write_text(SCENE)
    run_cli("render", str(scene), "--width", "88", "--height", "10", "--samples", "1",
            "-o", str(out), "--quiet")
    pair = godel.render(scene, progress=False, **SMALL)
    for eye in ("left", "right"):
        image = godel.read(out / f"{NAME}.{eye}.exr")
        assert type(image) is godel.Image and image.stereo is None
        assert image.header["scene_name"] == f"{NAME}.{eye}"
        assert_same_channels(image, pair.eye(eye))
        assert np.array_equal(image.rgb(), pair.eye(eye).rgb())
        with pytest.raises(ValueError, match="not a stereo pair"):
            image.eye(eye)


def test_what_belongs_to_one_eye_is_refused_on_the_pair(out):
    pair = godel.render(SCENE, progress=False, **SMALL)
    choose = r"use img\.eye\('left'\) or img\.eye\('right'\)"
    with pytest.raises(ValueError, match=choose + r", as img\.eye\('left'\)\['g'\]"):
        pair["g"]
    for refused in (lambda: pair.channels, lambda: "g" in pair, lambda: pair.header,
                    lambda: pair.hdr(), lambda: pair.save(out / "pair.exr")):
        with pytest.raises(ValueError, match=choose):
            refused()
    assert list(out.iterdir()) == []
    for name in ("middle", "Left", "", 0):
        with pytest.raises(ValueError) as raised:
            pair.eye(name)
        assert str(raised.value) == f"eye: must be 'left' or 'right', got {name!r}"
    mono = godel.render(with_stereo(None), progress=False, **SMALL)
    with pytest.raises(ValueError) as raised:
        mono.eye("left")
    assert str(raised.value) == (
        "eye: this image is one picture, not a stereo pair (a scene with [camera] stereo "
        "renders both eyes); no eye 'left'"
    )
    assert repr(pair) == (
        f"<godel.Image '{NAME}': stereo pair, anaglyph, separation 0.1 a; 88×10 samples per "
        "eye, 1² per pixel>"
    )
