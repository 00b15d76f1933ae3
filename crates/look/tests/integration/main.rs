//! The look crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p look --test integration look`.

mod common;

mod look;
mod look_input;
