"""The progress bar of long renders: tqdm's when it is installed (a widget in Jupyter when
ipywidgets is installed too, else text), else a plain line on standard error rewritten in place, in the
command line's words (``tracing NAME [...] 42% 1234/5678 px, 4213 px/s, ETA 3s``)."""

from __future__ import annotations

import sys
import time
from typing import Protocol


class Bar(Protocol):
    def update_to(self, done: int) -> None: ...

    def close(self) -> None: ...


class _Tqdm:
    """tqdm, advanced to an absolute count."""

    def __init__(self, total: int, name: str) -> None:
        try:
            import ipywidgets  # noqa: F401 (tqdm's Jupyter widget needs it)
            from tqdm.auto import tqdm
        except ImportError:
            from tqdm import tqdm  # text, also in Jupyter

        self._bar = tqdm(total=total, desc=f"tracing {name}", unit="px", unit_scale=True)

    def update_to(self, done: int) -> None:
        self._bar.update(done - self._bar.n)

    def close(self) -> None:
        self._bar.close()


class _Plain:
    """A one-line bar on standard error, at most five updates a second."""

    WIDTH = 30

    def __init__(self, total: int, name: str) -> None:
        self._total = max(total, 1)
        self._name = name
        self._started = time.monotonic()
        self._shown = 0.0
        self._done = 0

    def update_to(self, done: int) -> None:
        self._done = done
        now = time.monotonic()
        if now - self._shown >= 0.2:
            self._shown = now
            self._draw(now)

    def _draw(self, now: float) -> None:
        fraction = min(self._done / self._total, 1.0)
        filled = int(fraction * self.WIDTH)
        elapsed = max(now - self._started, 1e-9)
        rate = self._done / elapsed
        eta = f"{(self._total - self._done) / rate:.0f}s" if rate > 0 else "–"
        bar = "=" * filled + (">" if filled < self.WIDTH else "") + " " * (self.WIDTH - filled - 1)
        sys.stderr.write(
            f"\rtracing {self._name} [{bar[: self.WIDTH]}] {fraction:4.0%} "
            f"{self._done}/{self._total} px, {rate:.0f} px/s, ETA {eta}"
        )
        sys.stderr.flush()

    def close(self) -> None:
        self._draw(time.monotonic())
        sys.stderr.write("\n")
        sys.stderr.flush()


def bar(total: int, name: str) -> Bar:
    """A progress bar over ``total`` rays of the scene ``name``."""
    try:
        return _Tqdm(total, name)
    except ImportError:
        return _Plain(total, name)
