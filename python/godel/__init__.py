"""godel in Python: see the Gödel universe from inside, from a notebook.

Calls godel's Rust crates directly (no subprocess), through the same code as the ``godel``
command line, so that the numbers are the command line's, bit for bit:

- :func:`render` traces a scene into an :class:`Image` (``godel render``);
- :func:`read` reads a data file any ``godel`` command wrote;
- :class:`Image`: the channels as numpy arrays, :meth:`Image.rgb` / :meth:`Image.hdr`
  shade it as ``godel shade`` does, :meth:`Image.save` writes the data file;
- :class:`StereoImage`: a stereo scene's two eyes (``img.eye("left")``), their picture in
  the pair's layout;
- :func:`geodesic`: one light ray or massive particle (``godel geodesic``);
- :func:`connect`: every light ray from a source at rest to an event (``godel connect``).

Conventions (docs/guide/src/how-it-works.md, docs/physics.md): c = 1, signature (−,+,+,+), Gödel parameter
``a``, optical horizon at r = 2a, pseudo-Cartesian coordinates (t, x, y, z) with
x = r cos φ, y = r sin φ. Bad input raises ``ValueError`` with the command line's message,
naming the file, line and field of a scene, or the keyword argument (an empty path too); a
file that cannot be read or written raises ``OSError``: ``FileNotFoundError`` when missing,
``IsADirectoryError`` for a folder.
"""

import os
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _godel, _progress
from ._image import Image
from ._stereo import Stereo, StereoImage

__all__ = ["Image", "Stereo", "StereoImage", "connect", "geodesic", "read", "render"]

SceneLike = Union[str, "os.PathLike[str]", None]


def _scene_source(scene: SceneLike) -> Tuple[Optional[str], Optional[str]]:
    """(path, text) of a scene argument: a path, TOML text (a str with a line break), or None."""
    if scene is None:
        return None, None
    if isinstance(scene, str) and "\n" in scene:
        return None, scene
    return os.fspath(scene), None


def render(
    scene: SceneLike = None,
    width: Optional[int] = None,
    height: Optional[int] = None,
    samples: Optional[int] = None,
    method: Optional[str] = None,
    max_past: Optional[float] = None,
    threads: Optional[int] = None,
    progress: bool = True,
    metric: Optional[str] = None,
    a: Optional[float] = None,
    m2: Optional[float] = None,
    omega: Optional[float] = None,
) -> Image:
    """Traces a scene, as ``godel render`` does, and returns its :class:`Image`.

    ``scene`` is a path to a scene file, TOML text (any ``str`` with a line break), or None
    for the built-in reference scene. ``width``, ``height``, ``samples`` (rays per pixel, a
    square number), ``method`` (``"numeric"`` or ``"exact"``) and ``max_past`` (how far
    into the past rays are followed, coordinate time) replace the scene's fields for this
    render and are checked like the scene file; ``threads`` is the number of worker threads
    (default: one per core; at most 8 per core). The records are those ``godel render``
    writes for the same scene and overrides, bit for bit, whatever the thread count.

    ``metric`` (``"godel"``, ``"godel-type"``, ``"minkowski"``), ``a``, ``m2`` and ``omega``
    replace the scene's spacetime as ``godel render --metric --a --m2 --omega`` do: a new
    ``metric`` takes its constants from these arguments alone (the scene's are dropped), so
    ``render(metric="godel-type", m2=0.5, omega=0.7)`` renders the built-in scene in that
    member of the Gödel-type family (docs/physics.md, "The Gödel-type family"; with the
    built-in scene's method, numeric; ``method="exact"`` follows the member's closed forms).

    A stereo scene (``[camera] stereo``) traces both eyes, as ``godel render`` does, and
    returns a :class:`StereoImage`: ``img.eye("left")`` and ``img.eye("right")`` are the
    images of its ``NAME.left.exr`` and ``NAME.right.exr``, ``img.rgb()`` the picture of
    both in the pair's layout; ``img["g"]`` raises ``ValueError`` (choose an eye).

    ``progress`` shows a progress bar (tqdm's when installed, in Jupyter too, else a plain
    line on standard error). Ctrl-C (or a notebook's interrupt) stops the render within one
    tile per thread and raises ``KeyboardInterrupt``. A bad scene or value raises
    ``ValueError`` with the command line's message (``file:line:column: field: …``), as
    does an empty ``scene`` path; a scene file (or an image texture it names) that is
    missing raises ``FileNotFoundError``, a folder in its place ``IsADirectoryError``.
    """
    path, text = _scene_source(scene)
    job = _godel.RenderJob(path, text, width, height, samples, method, max_past, threads,
                           metric, a, m2, omega)
    bar = _progress.bar(job.total, job.name) if progress else None
    ended = False
    try:
        while not job.wait(0.1):
            if bar is not None:
                bar.update_to(job.done)
        ended = True
    finally:
        if not ended:
            # Interrupted (or any other exception): stop tracing, and wait for the tiles
            # under way so that no work outlives the call.
            job.cancel()
            job.wait(None)
        if bar is not None:
            bar.update_to(job.done)
            bar.close()
    eyes = [Image(data, summary) for data, summary in job.result()]
    if job.stereo is None:
        return eyes[0]
    return StereoImage(eyes[0], eyes[1], Stereo(*job.stereo), job.scene)


def read(path: Union[str, "os.PathLike[str]"]) -> Image:
    """Reads a data file that ``godel`` wrote (``godel render``, ``look``, ``merge``, a
    sequence's ``keep_data``, :meth:`Image.save`). A missing file raises
    ``FileNotFoundError``, a damaged one ``ValueError``, with the command line's message; a
    folder raises ``IsADirectoryError``, an empty path ``ValueError``."""
    return Image(_godel.Data.read(os.fspath(path)))


def geodesic(
    a: Optional[float] = None,
    position: Sequence[float] = (0.0, 0.0, 0.0),
    time: float = 0.0,
    direction: Sequence[float] = (1.0, 0.0, 0.0),
    speed: Optional[float] = None,
    past: bool = True,
    method: Optional[str] = None,
    samples: int = 100,
    max_past: Optional[float] = None,
    metric: str = "godel",
    m2: Optional[float] = None,
    omega: Optional[float] = None,
) -> Dict[str, Union[np.ndarray, str]]:
    """One geodesic of Gödel's universe (``a``, default 1), or of a member of the Gödel-type
    family (``metric="godel-type"`` with ``m2`` and ``omega``), as ``godel geodesic``
    computes it.

    It starts at the event (``time``, ``position`` = (x, y, z)) along ``direction`` (any
    non-zero length), given in the local frame of the observer at rest there. Without
    ``speed`` it is a light ray (affine parameter λ); with ``speed`` in [0, 1) a massive
    particle of that speed in that frame (λ is its proper time). ``past`` follows it into
    the past (as godel's rays are traced), else into the future. ``method`` ``"exact"``
    evaluates the closed form carried by an isometry, ``"numeric"`` integrates the geodesic
    equations (DOP853); both give the same curve. The default is ``"exact"``. It
    stops where |t − time| reaches ``max_past``, or by default after one loop (back on its
    starting axis, or at the latest after |t − time| = 2√2·π·a; in the family with
    a = 1/(√2·Ω)).

    The family (docs/physics.md, "The Gödel-type family"): ds² = −(dt + H dφ)² + dρ² +
    D² dφ² + dz² with vorticity ``omega`` = Ω > 0 and ``m2`` = m² of any sign, in
    coordinates x = ρ cos φ, y = ρ sin φ with ρ the proper radius. Gödel's universe with
    parameter a is the member ``m2=1/a**2, omega=1/(sqrt(2)*a)`` (its r = 2a sinh(ρ/2a)).
    ``a`` is refused with it, and ``m2``, ``omega`` with ``metric="godel"``; the ranges are
    those of scenes (1/(√2Ω) within [1e-6, 1e6], |m²| ≤ 100Ω², the start's ρ at most 30/m
    for m² > 0 and at most π/μ − ρ_c for m² = −μ² < 0).

    Returns ``samples`` points (2 to 1,000,000) evenly spaced in λ, first at the start,
    last at the stop, as float64 arrays: ``lambda``, ``t``, ``x``, ``y``, ``z``, and
    ``tangent`` (samples × 4: dt/dλ, dx/dλ, dy/dλ, dz/dλ); and ``stop``, why it stopped
    (``"axis_return"``, ``"time_reached"``, ``"affine_limit"``).
    """
    if method is None:
        method = "exact"
    stop, columns = _godel.geodesic(
        str(metric),
        None if a is None else float(a),
        None if m2 is None else float(m2),
        None if omega is None else float(omega),
        _vector(position, 3, "position"),
        float(time),
        _vector(direction, 3, "direction"),
        None if speed is None else float(speed),
        bool(past),
        str(method),
        int(samples),
        None if max_past is None else float(max_past),
    )
    arrays = {name: np.frombuffer(raw, dtype="=f8").copy() for name, raw in columns}
    tangent = np.stack([arrays.pop(k) for k in ("k_t", "k_x", "k_y", "k_z")], axis=-1)
    return {**arrays, "tangent": tangent, "stop": stop}


def connect(
    source: Sequence[float],
    target: Sequence[float],
    a: Optional[float] = None,
    windings: int = 2,
    metric: str = "godel",
    m2: Optional[float] = None,
    omega: Optional[float] = None,
) -> List[Dict[str, object]]:
    """Every light ray from a source at rest to an event, as ``godel connect`` finds them, in
    Gödel's universe (``a``, default 1) or in a member of the Gödel-type family
    (``metric="godel-type"`` with ``m2`` and ``omega``, as for ``geodesic``).

    ``source`` is the source's position (x, y, z): it is at rest there at all times, so it
    has no time of its own. ``target`` is the receiving event (t, x, y, z). Rays exist only
    where the target lies within the source's optical horizon (distance 2a from the
    source's axis); there are two per winding in the source's plane and more off it,
    ``windings`` (0 to 1000) counting the loops a ray completes before it arrives. In a
    member x, y are ρ cos φ, ρ sin φ with ρ the proper radius (bounded as for ``geodesic``),
    and rays reach ρ < ρ_c from the source's axis, every event for m² ≥ 4Ω².

    Returns one dict per ray, latest emission first: ``t_emit`` (emission time),
    ``emission`` (the event t, x, y, z), ``travel_time``, ``winding``, ``branch``
    (``"outbound"`` or ``"inbound"`` half of its loop), ``departure`` (unit direction at
    the source) and ``look`` (where the receiver at rest sees the source), both in the
    local frames of observers at rest, ``lambda`` (affine length), ``area_distance`` (the
    source's area distance D: flux = L·g²/(4πD²)), ``g`` (frequency ratio received/emitted:
    1 between source and receiver at rest) and ``miss`` (how far the ray, re-evaluated from
    its emission, lands from the target).
    """
    source = tuple(source)
    if len(source) != 3:
        raise ValueError(
            f"source: expected the position (x, y, z) of a source at rest, got {len(source)} "
            "numbers (a source at rest shines at all times: it has no time of its own)"
        )
    if isinstance(windings, bool) or int(windings) != windings or windings < 0:
        raise ValueError(f"windings: must be a whole number from 0 to 1000, got {windings!r}")
    _rho, rays = _godel.connect(
        _vector(source, 3, "source"),
        _vector(target, 4, "target"),
        str(metric),
        None if a is None else float(a),
        None if m2 is None else float(m2),
        None if omega is None else float(omega),
        int(windings),
    )
    keys = ("emission", "travel_time", "winding", "branch", "departure", "look", "lambda",
            "area_distance", "g", "miss")
    out = []
    for ray in rays:
        item = dict(zip(keys, ray))
        for vector in ("emission", "departure", "look"):
            item[vector] = np.array(item[vector])
        item["t_emit"] = float(item["emission"][0])
        out.append(item)
    return out


def _vector(values: Sequence[float], n: int, keyword: str) -> List[float]:
    """``values`` as ``n`` floats, or ValueError naming ``keyword``."""
    try:
        out = [float(v) for v in values]
    except (TypeError, ValueError):
        raise ValueError(f"{keyword}: expected {n} numbers, got {values!r}") from None
    if len(out) != n:
        raise ValueError(f"{keyword}: expected {n} numbers, got {len(out)}")
    return out
