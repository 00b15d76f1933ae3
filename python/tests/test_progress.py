"""The progress bar: tqdm's when tqdm is installed, else the plain line on stderr; none with
progress=False. Each ends at the render's total of rays (pixels × samples)."""

from __future__ import annotations

import sys

import godel


def test_plain_bar_without_tqdm(monkeypatch, capfd):
    monkeypatch.setitem(sys.modules, "tqdm", None)  # `import tqdm` raises ImportError
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    godel.render(width=44, height=5)
    err = capfd.readouterr().err
    assert err.endswith("\n")
    last = err.rstrip("\n").split("\r")[-1]
    assert last.startswith("tracing reference [=") and " 100% 880/880 px, " in last, last


def test_tqdm_bar(capfd):
    import tqdm  # noqa: F401 (installed for the tests)

    godel.render(width=44, height=5)
    err = capfd.readouterr().err
    assert "tracing reference: 100%" in err and "880/880" in err, err


def test_no_bar(capfd):
    godel.render(width=44, height=5, progress=False)
    assert capfd.readouterr().err == ""
