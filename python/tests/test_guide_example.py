"""The guide's Python example (docs/guide/src/python.md, its first Python block) runs as
written and makes its picture (docs/guide/src/pictures/python.png is this picture, made by
the same code)."""

from __future__ import annotations

import re
import subprocess
import sys

from PIL import Image as PILImage

from conftest import REPO

GUIDE = REPO / "docs" / "guide" / "src"


def guide_example() -> str:
    text = (GUIDE / "python.md").read_text()
    return re.search(r"```python\n(.*?)```", text, re.S).group(1)


def test_the_guide_example_makes_its_picture(tmp_path):
    code = guide_example()
    assert "godel.render" in code and 'savefig("python.png"' in code
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    with PILImage.open(tmp_path / "python.png") as made, \
            PILImage.open(GUIDE / "pictures" / "python.png") as shown:
        assert made.size == shown.size == (1200, 300)
