"""The README's Python example runs as written and makes its picture (docs/python.png is
this picture, made by the same code)."""

from __future__ import annotations

import re
import subprocess
import sys

from PIL import Image as PILImage

from conftest import REPO


def readme_example() -> str:
    text = (REPO / "README.md").read_text()
    section = text[text.index("\n## Python\n") :]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_readme_example_makes_its_picture(tmp_path):
    code = readme_example()
    assert "godel.render" in code and 'savefig("python.png"' in code
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    with PILImage.open(tmp_path / "python.png") as made, \
            PILImage.open(REPO / "docs" / "python.png") as shown:
        assert made.size == shown.size == (1200, 300)
