"""Shared fixtures: the repository, the ``godel`` command line the module is compared with
(``target/debug/godel`` as ``cargo build`` makes it, or ``$GODEL_BIN``), and readers of the
files it writes that do not go through godel's own code (the OpenEXR module, Pillow)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import Dict

import numpy as np
import OpenEXR
import pytest
from PIL import Image as PILImage

REPO = Path(__file__).resolve().parents[2]


def godel_binary() -> Path:
    path = Path(os.environ.get("GODEL_BIN", REPO / "target" / "debug" / "godel"))
    assert path.is_file(), f"no godel binary at {path}: run `cargo build` (or set GODEL_BIN)"
    return path


def run_cli(*args: str, check: bool = True) -> subprocess.CompletedProcess:
    """Runs the command line; with ``check`` it must succeed."""
    done = subprocess.run(
        [str(godel_binary()), *args], capture_output=True, text=True, cwd=REPO, timeout=600
    )
    if check:
        assert done.returncode == 0, f"godel {' '.join(args)}: {done.stderr}"
    return done


def cli_error(*args: str) -> str:
    """The message of a command that must fail: its stderr without ``error: ``."""
    done = run_cli(*args, check=False)
    assert done.returncode != 0, f"godel {' '.join(args)} succeeded"
    line = done.stderr.strip().splitlines()[-1]
    assert line.startswith("error: "), done.stderr
    return line[len("error: ") :]


def read_exr(path: Path) -> Dict[str, np.ndarray]:
    """Every channel of an EXR file by the OpenEXR module."""
    with OpenEXR.File(str(path), separate_channels=True) as f:
        return {name: np.array(ch.pixels) for name, ch in f.channels().items()}


def read_png(path: Path) -> np.ndarray:
    with PILImage.open(path) as im:
        return np.asarray(im.convert("RGB"))


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal element by element, bit for bit (NaN included), as float32."""
    a = np.ascontiguousarray(a, dtype=np.float32)
    b = np.ascontiguousarray(b, dtype=np.float32)
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))


@pytest.fixture
def out(tmp_path: Path) -> Path:
    return tmp_path
