//! The render crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p render --test integration falling`.
//! proptest keeps the seeds of past failures in `tests/proptest-regressions/MODULE.txt` (its
//! default: beside the folder that holds this `main.rs`).

mod common;

mod cancel;
mod chord;
mod coordinates;
mod determinism;
mod exact;
mod falling;
mod family_exact;
mod far;
mod godel_type;
mod graze;
mod images;
mod inside;
mod lighting;
mod map;
mod minkowski;
mod observer;
mod polarization;
mod reject;
mod scenes;
mod surroundings;
mod worldline;
