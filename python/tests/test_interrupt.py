"""Ctrl-C stops a render: a Python process rendering a scene far too large to finish gets a
real SIGINT once its progress bar has moved, raises KeyboardInterrupt out of godel.render
with the rays traced so far fewer than the render's total, and renders again afterwards.
The progress bar is tqdm's when tqdm is installed, else the plain line on stderr."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap

from conftest import REPO

SCRIPT = textwrap.dedent(
    """
    import signal
    import sys
    import godel
    from godel import _progress

    # Python raises KeyboardInterrupt on SIGINT only where SIGINT was not ignored when it
    # started; a shell's background job inherits it ignored. A user's Ctrl-C reaches a
    # process with the default handler: give this one that handler whatever started it.
    signal.signal(signal.SIGINT, signal.default_int_handler)

    class Spy:
        # Records what the progress bar is shown; says once when tracing is under way.
        def __init__(self, inner, total):
            self.inner, self.total, self.done = inner, total, 0
        def update_to(self, done):
            self.inner.update_to(done)
            first, self.done = self.done == 0 and done > 0, done
            if first:
                print("tracing", flush=True)
        def close(self):
            self.inner.close()

    spies = []
    make = _progress.bar
    def bar(total, name):
        spies.append(Spy(make(total, name), total))
        return spies[-1]
    _progress.bar = bar

    try:
        # 1.2e7 rays: minutes of work on any machine.
        godel.render(width=1500, height=2000, samples=4, max_past=60.0)
    except KeyboardInterrupt:
        spy = spies[-1]
        print(f"interrupted {spy.done} {spy.total}", flush=True)
        again = godel.render(width=44, height=5, progress=False)
        print(f"again {int((again['status'] == 0).sum())}", flush=True)
        sys.exit(0)
    print("finished", flush=True)
    sys.exit(1)
    """
)


def test_ctrl_c_stops_a_render_and_the_next_one_works(tmp_path):
    script = tmp_path / "long_render.py"
    script.write_text(SCRIPT)
    process = subprocess.Popen(
        [sys.executable, str(script)], cwd=REPO, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True,
    )
    try:
        assert process.stdout.readline().strip() == "tracing"
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=600)
    finally:
        process.kill()
    assert process.returncode == 0, f"{out}\n{err}"
    lines = out.splitlines()
    word, done, total = lines[0].split()
    assert word == "interrupted" and 0 < int(done) < int(total) == 1500 * 2000 * 4, lines[0]
    word, hits = lines[1].split()
    assert word == "again" and int(hits) > 0
    # The bar was drawn on stderr (tqdm's or the plain one), naming the scene.
    assert "tracing reference" in err
