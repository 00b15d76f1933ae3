"""The Gödel-type family (docs/physics.md, "The Gödel-type family") in Python:
godel.geodesic(metric="godel-type", m2=…, omega=…) against Gödel's universe (the member
m² = 1/a², Ω = 1/(√2 a), carried through r = 2a sinh(ρ/2a)) and against ``godel geodesic
--metric godel-type``; connect in a member (the Gödel member as Gödel, a member as
``godel connect --metric godel-type``); render(metric=…, m2=…, omega=…) recording the
member; bad arguments raise ValueError naming the keyword."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import godel
from conftest import REPO, run_cli


def test_the_godel_member_is_godels_universe_through_the_proper_radius():
    a = 0.8
    member = dict(metric="godel-type", m2=1 / a**2, omega=1 / (math.sqrt(2) * a))
    # From the axis the two charts' local frames agree: one direction, one ray (in the plane
    # and tilted out of it), one loop back to the axis.
    for direction in [(1.0, 0.0, 0.0), (0.3, -1.0, 0.6)]:
        common = dict(position=(0.0, 0.0, -0.1), time=0.5, direction=direction,
                      method="numeric", samples=41)
        ray = godel.geodesic(**member, **common)
        goedel = godel.geodesic(a=a, **common)
        rho = np.hypot(ray["x"], ray["y"])
        r = 2 * a * np.sinh(rho / (2 * a))
        assert np.allclose(ray["lambda"], goedel["lambda"], rtol=0, atol=1e-7)
        assert np.allclose(ray["t"], goedel["t"], rtol=0, atol=1e-7)
        assert np.allclose(ray["z"], goedel["z"], rtol=0, atol=1e-7)
        assert np.allclose(r, np.hypot(goedel["x"], goedel["y"]), rtol=0, atol=1e-7)
        # Same azimuth wherever it is defined (off the axis).
        off = rho > 1e-3
        phi = np.arctan2(ray["y"][off], ray["x"][off])
        phi_g = np.arctan2(goedel["y"][off], goedel["x"][off])
        assert np.allclose(np.angle(np.exp(1j * (phi - phi_g))), 0, atol=1e-6)
        assert rho.max() > 0.5 * a
        assert ray["stop"] == goedel["stop"] == "axis_return"


def test_a_member_equals_the_cli():
    ray = godel.geodesic(metric="godel-type", m2=-0.5, omega=0.75, position=(0.3, 0.1, 0.0),
                         direction=(0.2, 1.0, 0.1), past=False, samples=30)
    at = f"0,{math.hypot(0.3, 0.1)!r},{math.atan2(0.1, 0.3)!r},0"
    cli = json.loads(run_cli("geodesic", "--metric", "godel-type", "--m2", "-0.5", "--omega",
                             "0.75", "--at", at, "--dir", "0.2,1,0.1", "--samples", "30",
                             "--format", "json").stdout)
    assert (cli["m2"], cli["omega"]) == (-0.5, 0.75)
    for key in ("lambda", "t", "x", "y", "z"):
        expected = np.array([s[key] for s in cli["samples"]])
        assert np.allclose(ray[key], expected, rtol=1e-9, atol=1e-9), key
    assert ray["stop"] == cli["stop"]


@pytest.mark.parametrize("kwargs,keyword", [
    (dict(metric="godel-type", omega=1.0), "m2"),
    (dict(metric="godel-type", m2=1.0), "omega"),
    (dict(metric="godel-type", m2=1.0, omega=0.0), "omega"),
    (dict(metric="godel-type", m2=1.0, omega=-2.0), "omega"),
    (dict(metric="godel-type", m2=1.0, omega=math.nan), "omega"),
    (dict(metric="godel-type", m2=1.0, omega=1e300), "omega"),
    (dict(metric="godel-type", m2=math.inf, omega=1.0), "m2"),
    (dict(metric="godel-type", m2=-101.0, omega=1.0), "m2"),
    (dict(metric="godel-type", m2=1.0, omega=1.0, a=1.0), "a"),
    (dict(metric="godel-type", m2=4.0, omega=1.0, position=(15.01, 0, 0)), "position"),
    (dict(metric="godel-type", m2=-1.0, omega=0.5, position=(0, 1.58, 0)), "position"),
    (dict(m2=1.0), "m2"),
    (dict(omega=1.0), "omega"),
    (dict(metric="kerr"), "metric"),
])
def test_bad_family_arguments_name_the_keyword(kwargs, keyword):
    with pytest.raises(ValueError, match=f"^{keyword}: "):
        godel.geodesic(**kwargs)


def test_render_in_a_member_records_it():
    image = godel.render(width=22, height=4, samples=1, metric="godel-type", m2=0.5,
                         omega=0.7, progress=False)
    header = image.header
    assert header["metric"] == "godel-type"
    assert (header["m2"], header["omega"]) == (0.5, 0.7)
    assert 'metric = "godel-type"' in image.scene


def test_a_lit_member_lights_its_ball_and_the_blocker_shades_it():
    scene = REPO / "scenes" / "lit-godel-type.toml"
    lit = godel.render(str(scene), width=180, height=20, progress=False)
    assert lit.header["metric"] == "godel-type"
    light, ball = lit["light_0"], lit["object"] == 0
    assert np.all(light[ball] >= 0) and np.any(light[ball] > 0)
    # Without the blocker (object 1) the ball is lit where the blocker shaded it.
    text = scene.read_text()
    start = text.index('[[object]]\nname = "blocker"')
    unblocked = godel.render(text[:start] + text[text.index("[[light]]"):], width=180,
                             height=20, progress=False)
    both = ball & (unblocked["object"] == 0)
    shaded = both & (light < 0.999 * unblocked["light_0"])
    assert shaded.sum() >= 3
    assert np.all(light[both] <= unblocked["light_0"][both] * (1 + 1e-6))


@pytest.mark.parametrize("kwargs,keyword", [
    (dict(m2=0.5), "m2"),
    (dict(metric="godel-type", m2=0.5, omega=-1.0), "omega"),
    (dict(metric="godel-type", m2=500.0, omega=1.0), "m2"),
    (dict(metric="godel-type", m2=0.5, omega=0.7, a=1.0), "a"),
    (dict(metric="godel-type", m2=0.5), "metric"),
])
def test_bad_render_spacetimes_name_the_keyword(kwargs, keyword):
    with pytest.raises(ValueError, match=f"^{keyword}: spacetime\\."):
        godel.render(width=22, height=4, progress=False, **kwargs)


def test_connect_in_the_godel_member_is_godels_through_the_proper_radius():
    a = 0.8
    member = dict(metric="godel-type", m2=1 / a**2, omega=1 / (math.sqrt(2) * a))
    # Source and target on the x axis, where the two charts' static frames agree.
    source, target = (0.3, 0.0, -0.2), (0.5, 0.9, 0.0, 0.7)
    rays = godel.connect(source, target, **member)
    stretch = lambda rho: 2 * a * math.sinh(rho / (2 * a))
    theirs = godel.connect((stretch(0.3), 0.0, -0.2), (0.5, stretch(0.9), 0.0, 0.7), a=a)
    assert len(rays) == len(theirs) >= 6
    for mine, goedel in zip(rays, theirs):
        assert (mine["winding"], mine["branch"]) == (goedel["winding"], goedel["branch"])
        assert abs(mine["t_emit"] - goedel["t_emit"]) < 1e-9
        assert np.allclose(mine["departure"], goedel["departure"], rtol=0, atol=1e-8)
        area, want = mine["area_distance"], goedel["area_distance"]
        assert abs(area - want) < 1e-6 * want
        assert mine["miss"] < 1e-9


def test_connect_in_a_member_equals_the_cli():
    rays = godel.connect((0.3, 0.1, 0.0), (1.0, 0.2, -0.5, 0.8), metric="godel-type", m2=6.0,
                         omega=1.0, windings=1)
    to = f"{math.hypot(0.3, 0.1)!r},{math.atan2(0.1, 0.3)!r},0"
    frm = f"1,{math.hypot(0.2, -0.5)!r},{math.atan2(-0.5, 0.2)!r},0.8"
    cli = json.loads(run_cli("connect", "--metric", "godel-type", "--m2", "6", "--omega", "1",
                             "--from", frm, "--to-source", to, "--windings", "1",
                             "--format", "json").stdout)
    assert len(rays) == len(cli["rays"]) >= 1
    for mine, theirs in zip(rays, cli["rays"]):
        assert abs(mine["t_emit"] - theirs["emission"]["t"]) < 1e-9
        area, want = mine["area_distance"], theirs["area_distance"]
        assert abs(area - want) < 1e-9 * want
        assert mine["branch"] == theirs["branch"]


@pytest.mark.parametrize("kwargs,keyword", [
    (dict(metric="godel-type", omega=1.0), "m2"),
    (dict(metric="godel-type", m2=1.0, omega=1.0, a=1.0), "a"),
    (dict(m2=1.0), "m2"),
    (dict(metric="godel-type", m2=-1.0, omega=1.0, source=(2.5, 0, 0)), "source"),
    (dict(metric="godel-type", m2=-1.0, omega=1.0, target=(0, 0, 2.5, 0)), "target"),
    (dict(metric="godel-type", m2=1.0, omega=1.0, target=(1, 0.3, 0, 2)), "target"),
])
def test_bad_connect_arguments_name_the_keyword(kwargs, keyword):
    args = {"source": (0.3, 0, 0), "target": (1, 0, 0.5, 0), **kwargs}
    with pytest.raises(ValueError, match=f"^{keyword}: "):
        godel.connect(**args)
