#!/usr/bin/env bash
# Runs every test of godel on a fresh machine. Installs, quietly and only when missing,
# what the tests need beyond cargo. CI (.ci/run) calls exactly this script.
set -euo pipefail
cd "$(dirname "$0")/.."

# The dev/test profile is optimized (Cargo.toml): physics tests are heavy.
cargo build --workspace --all-targets --quiet
cargo test --workspace --no-fail-fast
