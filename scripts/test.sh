#!/usr/bin/env bash
# Runs every test of godel on a fresh machine. Installs, quietly and only when missing,
# what the tests need beyond cargo. CI (.ci/run) calls exactly this script.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage's end, with the minutes and seconds since the start, on stderr: where the time
# of a run (CI's included) goes.
stage() { echo "test.sh: $1 done at $((SECONDS / 60))m$((SECONDS % 60))s" >&2; }

# What the tests need beyond cargo, installed where missing while the workspace builds (the
# build needs none of it; on a fresh machine the downloads take a minute or two). From Debian,
# in one apt-get run (each apt-get update took seconds of a fresh machine's run):
# - chromium: the viewer's browser tests (crates/godel/tests/integration/browser.rs)
#   drive Debian's chromium through playwright-core (playwright's own browser download cannot
#   work here, and is not used). The page shades with WebGL2: headless chromium renders it in
#   software on SwiftShader, which Debian's chromium package ships
#   (/usr/lib/chromium/libvk_swiftshader.so); no GPU is needed.
# - Mesa's EGL: `godel render --gpu` (crates/gpu) loads libEGL at run time; without a GPU,
#   Mesa's llvmpipe renders its OpenGL ES 3 context in software (crates/gpu/tests,
#   crates/godel/tests/integration/gpu_cli.rs).
# - glslang-tools: Khronos' reference GLSL compiler checks every kernel a host builds
#   (crates/gpu/tests/integration/glslang.rs).
# - Python's venv for the Python package's tests, OpenMPI and libclang (rsmpi's bindgen) for
#   the `mpi` feature's (below).
need=()
command -v chromium >/dev/null || need+=(chromium)
command -v node >/dev/null || need+=(nodejs npm)
dpkg -s libegl1 libegl-mesa0 libgl1-mesa-dri >/dev/null 2>&1 || need+=(libegl1 libegl-mesa0 libgl1-mesa-dri)
command -v glslangValidator >/dev/null || need+=(glslang-tools)
python3 -c 'import ensurepip, venv' 2>/dev/null || need+=(python3 python3-venv)
{ command -v mpirun >/dev/null && dpkg -s openmpi-bin libopenmpi-dev libclang-dev >/dev/null 2>&1; } \
    || need+=(openmpi-bin libopenmpi-dev libclang-dev)
venv=target/python-venv
tools() {
    if ((${#need[@]})); then
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}" >/dev/null
    fi
    # The Python package's tests (below) run in a virtual environment under target/, made
    # when missing, with their tools installed when missing.
    [ -x "$venv/bin/python" ] || python3 -m venv "$venv"
    "$venv/bin/python" -c 'import maturin, numpy, pytest, OpenEXR, matplotlib, nbclient, nbformat, ipykernel, tqdm' 2>/dev/null \
        || "$venv/bin/pip" install -q --disable-pip-version-check \
            'maturin>=1.9.4,<2' numpy pytest OpenEXR matplotlib nbclient nbformat ipykernel tqdm
    # playwright-core and TypeScript, pinned in tests/browser/package.json.
    [ -d tests/browser/node_modules/playwright-core ] && [ -x tests/browser/node_modules/.bin/tsc ] \
        || (cd tests/browser && npm ci --silent --no-audit --no-fund)
}
tools_log=$(mktemp)
(set -e; tools) >"$tools_log" 2>&1 &
tools_pid=$!
# On an early exit the installs are left to end: an apt-get cut short can leave dpkg half done.
trap 'wait "$tools_pid" 2>/dev/null || true; rm -f "$tools_log"' EXIT

# The dev/test profile is optimized (Cargo.toml): physics tests are heavy.
cargo build --workspace --all-targets --quiet
stage "the workspace's build"
wait "$tools_pid" || {
    cat "$tools_log" >&2
    echo "test.sh: what the tests need beyond cargo could not be installed" >&2
    exit 1
}
# The page (crates/viewer/page: ES modules with JSDoc types, the server's JSON typed in
# contract.d.ts) is type-checked by TypeScript: strict, no output; any type error fails the
# tests.
tests/browser/node_modules/.bin/tsc -p crates/viewer/page
stage "the tools the tests need and the page's type check"
cargo test --workspace --no-fail-fast
stage "the Rust tests"

# --- Python (issue 26): the package in python/ (docs/guide/src/python.md), installed with
# `pip install ./python` into the virtual environment made above, then its pytest tests,
# which compare it with the godel binary built above. maturin builds with the dev profile
# here, whose artifacts the workspace build above already made (.cargo/config.toml,
# python/Cargo.toml): only pyo3 and the module itself compile again.
PATH="$PWD/$venv/bin:$PATH" MATURIN_PEP517_ARGS="--profile dev" \
    "$venv/bin/pip" install -q --disable-pip-version-check --no-build-isolation --force-reinstall --no-deps ./python
"$venv/bin/python" -m pytest -q python/tests
stage "the Python package's build and tests"

# --- MPI (issue 6): the `mpi` feature needs OpenMPI, and libclang for rsmpi's bindgen
# (installed above); the default build needs neither. The tests start `mpirun -n 2`
# (crates/godel/tests/mpi.rs).
# The workspace's feature set plus godel's `mpi`: built as `-p godel --features mpi`, the
# shared dependencies (tokio, axum, render, gpu, ...) got another feature set and compiled
# again (about 40 crates); so only the MPI crates and godel compile here.
cargo test --workspace --features godel/mpi --test mpi --no-fail-fast
stage "the MPI build and tests"

# --- The user guide (issue 35): docs/guide is an mdBook, built into docs/guide/book. mdBook
# is not in Debian: it is installed from crates.io into target/tools when missing, without
# its default features (file watcher, live-reload server, search index; the book reads
# without them), unoptimized (--debug: it compiles in about half the time, and builds the
# guide in seconds all the same).
# mdBook exits 0 on a broken link, a missing picture or an include of a missing file, so
# scripts/check-guide.py then checks every link and picture of the built book and of
# README.md.
[ -x target/tools/bin/mdbook ] || cargo install mdbook --no-default-features --locked --debug \
    --version 0.5.4 --root target/tools --quiet
MDBOOK_LOG=warn target/tools/bin/mdbook build docs/guide
python3 scripts/check-guide.py
stage "the guide's build and check"
