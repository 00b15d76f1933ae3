"""``StereoImage``: the two eyes of a stereo scene (``[camera] stereo``) as
:func:`godel.render` traces them, each an ordinary :class:`Image`, and their picture in the
pair's layout, composed as ``godel shade`` composes it."""

import os
from typing import Any, Dict, Iterable, NamedTuple, Optional, Tuple, Union

import numpy as np

from . import _godel
from ._image import EYES, Image, _settings_json

#: What a pair refuses to do as one image, and what to do instead.
_ONE_EYE = (
    "a stereo pair holds two images, one per eye: use img.eye('left') or img.eye('right')"
)


class Stereo(NamedTuple):
    """A stereo pair's ``[camera] stereo``: the eyes' ``separation`` (units of a), the
    ``layout`` of their picture (``"side-by-side"``, ``"over-under"`` or ``"anaglyph"``)
    and the ``convergence`` distance where their axes meet (units of a; None: parallel)."""

    separation: float
    layout: str
    convergence: Optional[float]


class StereoImage(Image):
    """The two eyes of a stereo scene, as :func:`godel.render` returns them.

    ``img.eye("left")`` and ``img.eye("right")`` are each eye's :class:`Image`: the records
    of the data file ``godel render`` writes for it (``NAME.left.exr``, ``NAME.right.exr``),
    bit for bit, with all an image has (channels, ``rgb``, ``save``, …). ``img.stereo`` is
    the pair's :class:`Stereo`. :meth:`rgb` is the picture of both eyes in the layout.
    What belongs to one eye (its channels, ``img["g"]``, its header, ``hdr``, ``save``)
    raises ``ValueError`` on the pair, saying to choose an eye.
    """

    def __init__(self, left: Image, right: Image, stereo: Stereo, scene: str) -> None:
        # Not Image.__init__: the pair has no data of its own, only its eyes'.
        self._eyes = {"left": left, "right": right}
        self._scene = scene
        #: The pair's ``[camera] stereo``.
        self.stereo = stereo
        #: Each eye's summary line (rays, hits, failures, time), the left eye's first.
        self.summary = "\n".join(f"{name} eye: {img.summary}" for name, img in self._eyes.items())

    def eye(self, name: str) -> Image:
        """The image of eye ``name``, ``"left"`` or ``"right"`` (anything else raises
        ``ValueError``)."""
        if name not in EYES:
            raise ValueError(f"eye: must be 'left' or 'right', got {name!r}")
        return self._eyes[name]

    @property
    def channels(self) -> Dict[str, np.ndarray]:
        raise ValueError(_ONE_EYE)

    def __getitem__(self, name: str) -> np.ndarray:
        raise ValueError(f"{_ONE_EYE}, as img.eye('left')[{name!r}]")

    def __contains__(self, name: object) -> bool:
        raise ValueError(_ONE_EYE)

    @property
    def scene(self) -> str:
        """The pair's scene as rendered, overrides included (TOML text); each eye's image
        holds that eye's scene (``NAME.left``, observer at the eye)."""
        return self._scene

    @property
    def samples(self) -> int:
        """Samples per picture pixel along each side, as in each eye."""
        return self._eyes["left"].samples

    @property
    def shape(self) -> Tuple[int, int]:
        """(height, width) of each eye's stored channels."""
        return self._eyes["left"].shape

    @property
    def header(self) -> Dict[str, Any]:
        raise ValueError(_ONE_EYE)

    def rgb(self, shaders: Iterable[str] = ("texture",), **settings: Any) -> np.ndarray:
        """The picture of both eyes in the pair's layout, as ``godel shade NAME.left.exr -o
        picture.png`` makes it: each eye shaded as :meth:`Image.rgb` does with these
        ``shaders`` and ``settings`` (over the left eye's defaults), then side by side (2W
        wide), over-under (2H tall) or as an anaglyph (red from the left eye's brightness,
        green and blue from the right eye's): (H, W, 3) uint8 sRGB."""
        left, right = self._eyes["left"], self._eyes["right"]
        width, height, raw = _godel.shade_pair(
            left._data, right._data, self.stereo.layout, _settings_json(shaders, settings)
        )
        return np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3).copy()

    def hdr(self, shaders: Iterable[str] = ("texture",), **settings: Any) -> np.ndarray:
        raise ValueError(f"{_ONE_EYE}: a linear picture is one eye's, as img.eye('left').hdr()")

    def save(self, path: Union[str, os.PathLike]) -> None:
        raise ValueError(
            f"{_ONE_EYE}: a pair is two data files, as img.eye('left').save('NAME.left.exr')"
        )

    def __repr__(self) -> str:
        height, width = self.shape
        name = self._eyes["left"].header["scene_name"].removesuffix(".left")
        return (
            f"<godel.Image {name!r}: stereo pair, {self.stereo.layout}, separation "
            f"{self.stereo.separation} a; {width}×{height} samples per eye, "
            f"{self.samples}² per pixel>"
        )
