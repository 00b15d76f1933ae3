"""``Image``: a traced image, its channels as numpy arrays, shaded as ``godel shade`` shades
it, written as a data file the command line reads."""

import json
import os
from typing import Any, Dict, Iterable, Optional, Tuple, Union

import numpy as np

from . import _godel

#: Types of the channels that are not float32.
_DTYPES = {"object": np.int32, "status": np.uint8}

#: The eyes of a stereo pair, as ``Image.eye`` names them.
EYES = ("left", "right")


class Image:
    """A traced image: what ``godel render`` writes into its data file, in memory.

    Made by :func:`godel.render` or :func:`godel.read`. Channels (see the guide,
    docs/guide/src/data-file.md) are H×W numpy arrays of the stored image (with ``samples = s²`` it is s times
    wider and taller than the picture, every sample kept):

    - ``object`` (int32): index of the object hit in scene order, −1 for none;
    - ``status`` (uint8): 0 hit, 1 nothing within ``max_past``, 2 step budget spent,
      3 integration failed, 4 not traced, 5 work limit;
    - float32: ``u``, ``v``, ``g``, ``t_emit``, ``x``, ``y``, ``z``, ``lambda``, ``dir_x``,
      ``dir_y``, ``dir_z``, ``cos_i``, ``view_x``, ``view_y``, ``view_z``, ``pol_x``,
      ``pol_y``, ``pol_z`` (the pixel's screen-up carried back to the emitter, in its body
      axes; docs/physics.md, "Polarization") and ``light_0``, ``light_1``, … (one per light),
      NaN where the data file holds NaN: the physical channels where nothing was hit,
      ``view_*`` where nothing was traced.

    ``image["g"]`` is ``image.channels["g"]``. Row 0 is the top row.

    A stereo scene renders as a pair (``godel.StereoImage``): ``image.eye("left")`` and
    ``image.eye("right")`` are then each eye's image. The data file of one eye
    (``NAME.left.exr``) reads as one image, as any data file.
    """

    #: A stereo pair's ``[camera] stereo`` (``godel.Stereo``); None for one picture.
    stereo = None

    def __init__(self, data: _godel.Data, summary: str = "") -> None:
        self._data = data
        self._channels: Optional[Dict[str, np.ndarray]] = None
        #: The render's summary line (rays, hits, failures, time); empty for a file read.
        self.summary = summary

    @property
    def channels(self) -> Dict[str, np.ndarray]:
        """Every channel by name, as the data file stores it (see the class doc)."""
        if self._channels is None:
            width, height = self._data.size
            channels = {}
            for name, dtype, raw in self._data.planes():
                values = np.frombuffer(raw, dtype=dtype).reshape(height, width)
                channels[name] = values.astype(_DTYPES.get(name, np.float32), copy=False)
            self._channels = channels
        return self._channels

    def __getitem__(self, name: str) -> np.ndarray:
        return self.channels[name]

    def eye(self, name: str) -> "Image":
        """One eye of a stereo pair (``"left"`` or ``"right"``): this image is one picture,
        so it raises ``ValueError``."""
        raise ValueError(
            f"eye: this image is one picture, not a stereo pair (a scene with [camera] stereo "
            f"renders both eyes); no eye {name!r}"
        )

    def __contains__(self, name: object) -> bool:
        return name in self.channels

    @property
    def scene(self) -> str:
        """The scene as rendered, overrides included (TOML text)."""
        return self._data.scene

    @property
    def samples(self) -> int:
        """Samples per picture pixel along each side, s (s² rays per pixel)."""
        return self._data.supersample

    @property
    def shape(self) -> Tuple[int, int]:
        """(height, width) of the stored channels (samples, not picture pixels)."""
        width, height = self._data.size
        return (height, width)

    @property
    def header(self) -> Dict[str, Any]:
        """The data file's header: scene name, camera, observer time, metric, a, method and
        the object names (``objects``, indexed by the ``object`` channel)."""
        return dict(self._data.header())

    def rgb(self, shaders: Iterable[str] = ("texture",), **settings: Any) -> np.ndarray:
        """The picture as ``godel shade … -o picture.png`` makes it: (H, W, 3) uint8 sRGB at
        picture size (samples box-filtered), overlays included.

        ``shaders`` are layers whose colours multiply: ``texture``, ``frequency``, ``time``,
        ``light``. ``settings`` are the fields of a ``godel shade --settings`` file, e.g.
        ``brightness="physical", exposure=0.5, ev=-1, grid=True,
        time={"mode": "travel", "travel_min": 0, "travel_max": 12},
        objects={"earth": {"temperature": 4000}}``; missing ones keep the data file's
        defaults. A bad field raises ``ValueError`` naming it.
        """
        width, height, raw = self._data.shade(_settings_json(shaders, settings), False)
        return np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3).copy()

    def hdr(self, shaders: Iterable[str] = ("texture",), **settings: Any) -> np.ndarray:
        """The picture as ``godel shade … -o picture.exr`` makes it: (H, W, 3) float32 linear,
        scene-referred RGB (no exposure compensation, tone curve or overlays, so ``ev`` and
        ``grid`` are refused). Same ``shaders`` and ``settings`` as :meth:`rgb`."""
        for display_only in ("ev", "grid"):
            if display_only in settings:
                raise ValueError(
                    f"{display_only}: has no effect on a linear picture (no exposure, tone "
                    "curve or overlays): use rgb()"
                )
        width, height, raw = self._data.shade(_settings_json(shaders, settings), True)
        return np.frombuffer(raw, dtype="=f4").reshape(height, width, 3).copy()

    def save(self, path: Union[str, os.PathLike]) -> None:
        """Writes the data file to ``path``, through a temporary file and a rename: the same
        bytes as ``godel render`` writes for this image, readable by every ``godel`` command.

        ``path`` must end in ``.exr``, as a data file's name on the command line: any other
        name (``x.png`` is a picture's: see :meth:`rgb`, :meth:`hdr`) or an empty one raises
        ``ValueError``, a folder ``IsADirectoryError``, a missing folder
        ``FileNotFoundError``. A save that fails leaves no file behind, and an existing
        file at ``path`` as it was."""
        self._data.save(os.fspath(path))

    def __repr__(self) -> str:
        height, width = self.shape
        name = self.header["scene_name"]
        return f"<godel.Image {name!r}: {width}×{height} samples, {self.samples}² per pixel>"


def _settings_json(shaders: Iterable[str], settings: Dict[str, Any]) -> str:
    if isinstance(shaders, str):
        shaders = [shaders]
    return json.dumps({**settings, "shaders": list(shaders)})
