"""godel.geodesic and godel.connect: against ``godel geodesic`` and ``godel connect``
(JSON), and against physics computed here, independently: the Gödel metric written out in
numpy (the tangent is null, or of unit norm for a particle, and is the curve's derivative),
the loop time of light from the axis, a traced pixel's ray ending at its emission event, and
each connecting ray, traced forward from its emission, landing on the target."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import godel
from conftest import run_cli


def metric_norm(a: float, x, y, k) -> np.ndarray:
    """g(k, k) of Gödel's metric in pseudo-Cartesian coordinates (docs/physics.md,
    "The Gödel metric":
    ds² = −dt² − (√2 r²/a) dt dφ + dr²/(1 + (r/2a)²) + r²(1 − (r/2a)²) dφ² + dz²,
    with r² dφ = x dy − y dx and r dr = x dx + y dy), at points off the axis."""
    kt, kx, ky, kz = k[:, 0], k[:, 1], k[:, 2], k[:, 3]
    r2 = x * x + y * y
    s = r2 / (4 * a * a)
    ang = x * ky - y * kx  # r² dφ/dλ
    rad = x * kx + y * ky  # r dr/dλ
    return (
        -kt * kt
        - math.sqrt(2) / a * kt * ang
        + rad * rad / r2 / (1 + s)
        + (1 - s) * ang * ang / r2
        + kz * kz
    )


def cli_geodesic(position, time, direction, extra):
    x, y, z = position
    at = f"{time!r},{math.hypot(x, y)!r},{math.atan2(y, x)!r},{z!r}"
    text = run_cli("geodesic", "--at", at, "--dir", ",".join(map(repr, direction)),
                   "--format", "json", *extra).stdout
    return json.loads(text)


CASES = [
    # (position, time, direction, keywords, CLI flags)
    ((0.0, 0.0, 0.0), 0.0, (1.0, 0.0, 0.0), dict(), []),
    ((0.0, 0.0, 0.0), 0.0, (1.0, 0.5, 0.3), dict(method="numeric"), ["--method", "numeric"]),
    ((0.4, -0.3, 0.2), 1.5, (0.2, 1.0, -0.4), dict(max_past=5.0), ["--until-time", "5"]),
    ((0.4, -0.3, 0.2), 0.0, (0.0, 1.0, 0.0), dict(speed=0.7, past=False, max_past=4.0),
     ["--speed", "0.7", "--until-time", "4"]),
    ((1.2, 0.1, 0.0), 0.0, (-1.0, 0.0, 0.0), dict(speed=0.3, method="numeric", samples=40),
     ["--speed", "0.3", "--method", "numeric", "--samples", "40"]),
]


@pytest.mark.parametrize("position,time,direction,kwargs,flags", CASES)
def test_geodesic_equals_the_cli(position, time, direction, kwargs, flags):
    ray = godel.geodesic(position=position, time=time, direction=direction, **kwargs)
    method = kwargs.get("method", "exact")
    past = kwargs.get("past", True)
    extra = ["--method", method] if "--method" not in flags else []
    extra += ["--past"] if past else []
    cli = cli_geodesic(position, time, direction, flags + extra)
    samples = cli["samples"]
    assert len(ray["t"]) == len(samples) == kwargs.get("samples", 100)
    for key in ("lambda", "t", "x", "y", "z"):
        expected = np.array([s[key] for s in samples])
        assert np.allclose(ray[key], expected, rtol=1e-9, atol=1e-9), key
    assert ray["stop"] == cli["stop"]
    # Time starts to run the asked way (beyond r = 2a from the origin's axis, where rays
    # from off-axis starts may go, coordinate time need not be monotonic along them).
    assert (ray["t"][1] < ray["t"][0]) if past else (ray["t"][1] > ray["t"][0])


@pytest.mark.parametrize("position,time,direction,kwargs,flags", CASES)
def test_the_tangent_is_null_or_unit_and_is_the_derivative(position, time, direction, kwargs,
                                                            flags):
    a = 1.0
    ray = godel.geodesic(position=position, time=time, direction=direction, **kwargs)
    k, x, y = ray["tangent"], ray["x"], ray["y"]
    off_axis = x * x + y * y > 1e-6
    norm = metric_norm(a, x[off_axis], y[off_axis], k[off_axis])
    expected = -1.0 if "speed" in kwargs else 0.0
    assert np.allclose(norm, expected, atol=1e-8), norm
    # dx^μ/dλ by finite differences of the samples matches the tangent (second order).
    lam = ray["lambda"]
    for i, key in enumerate("txyz"):
        derivative = np.gradient(ray[key], lam)[1:-1]
        scale = np.abs(k[:, i]).max() + 1.0
        assert np.allclose(derivative, k[1:-1, i], atol=0.02 * scale), key


def test_light_from_the_axis_returns_after_one_loop():
    # Light rays from the axis come back to it after t = 2πa(√2 − 1) (docs/physics.md).
    for a in (1.0, 0.5):
        ray = godel.geodesic(a=a, direction=(0.3, 1.0, 0.0), samples=200)
        assert ray["stop"] == "axis_return"
        assert math.isclose(-ray["t"][-1], 2 * math.pi * a * (math.sqrt(2) - 1), rel_tol=1e-9)
        r = np.hypot(ray["x"], ray["y"])
        assert r[-1] < 1e-9 and r.max() < 2 * a  # inside the optical horizon


def test_a_pixels_ray_ends_at_its_emission_event():
    # The reference observer sits at rest on the axis: a pixel's camera direction (view_*)
    # is the local direction of its backward light ray, which reaches the emission event
    # (x, y, z) after the time −t_emit.
    image = godel.render(width=88, height=10, method="exact", progress=False)
    hit = np.argwhere(image["status"] == 0)
    assert len(hit) > 10
    for row, col in hit[:: max(len(hit) // 12, 1)]:
        view = [float(image[f"view_{c}"][row, col]) for c in "xyz"]
        t_emit = float(image["t_emit"][row, col])
        ray = godel.geodesic(direction=view, max_past=-t_emit, samples=2)
        end = np.array([ray["x"][-1], ray["y"][-1], ray["z"][-1]])
        emitted = np.array([image[c][row, col] for c in "xyz"], dtype=float)
        assert ray["stop"] == "time_reached"
        assert np.allclose(end, emitted, atol=2e-5), (row, col, end, emitted)


def test_connect_equals_the_cli_and_its_rays_land():
    source, target = (1.1 * math.cos(-0.6), 1.1 * math.sin(-0.6), 0.35), (0.0, 0.4 * math.cos(2),
                                                                         0.4 * math.sin(2), 0.1)
    rays = godel.connect(source=source, target=target)
    t, x, y, z = target
    cli = json.loads(run_cli(
        "connect", "--from", f"{t!r},{math.hypot(x, y)!r},{math.atan2(y, x)!r},{z!r}",
        "--to-source", f"{math.hypot(*source[:2])!r},{math.atan2(source[1], source[0])!r},"
                       f"{source[2]!r}", "--format", "json").stdout)["rays"]
    assert len(rays) == len(cli) >= 4
    for ray, expected in zip(rays, cli):
        e = expected["emission"]
        assert np.allclose(ray["emission"], [e["t"], e["x"], e["y"], e["z"]], atol=1e-9)
        assert ray["t_emit"] == ray["emission"][0]
        for key in ("travel_time", "lambda", "area_distance"):
            assert math.isclose(ray[key], expected[key], rel_tol=1e-9, abs_tol=1e-12), key
        for key in ("departure", "look"):
            assert np.allclose(ray[key], expected[key], atol=1e-9), key
        assert (ray["winding"], ray["branch"]) == (expected["winding"], expected["branch"])
        assert math.isclose(ray["g"], expected["g"], rel_tol=1e-12)
        assert ray["miss"] < 1e-9 and abs(ray["g"] - 1.0) < 1e-9
        # Independently: the light ray leaving the source along `departure` at the emission
        # event, followed forward for the travel time, arrives at the target.
        forward = godel.geodesic(position=ray["emission"][1:], time=ray["emission"][0],
                                 direction=ray["departure"], past=False,
                                 max_past=ray["travel_time"], samples=2)
        end = [forward[c][-1] for c in "txyz"]
        assert np.allclose(end, target, atol=1e-7), (end, target)
    # Latest emission first.
    emitted = [r["t_emit"] for r in rays]
    assert emitted == sorted(emitted, reverse=True)


def test_beyond_the_horizon_no_ray_connects():
    assert godel.connect(source=(2.2, 0.0, 0.0), target=(0.0, 0.0, 0.0, 0.0)) == []
