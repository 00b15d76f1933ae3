//! The datafile crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p datafile --test integration codec`.

mod atomic;
mod codec;
