//! The gpu crate's integration tests, one binary (the crate is linked once, not once per
//! file). One module: `cargo test -p gpu --test integration rounds`. The kernel on Mesa's
//! llvmpipe (and softpipe, in a process of its own: `softpipe`) against the CPU exact tracer,
//! its pieces against their Rust twins, its rules, and every variant through glslang.

mod common;

mod agreement;
mod check;
mod family;
mod faults;
mod glslang;
mod kept_probes;
mod kernel_rules;
mod probes;
mod rounds;
mod softpipe;
mod table;
mod threads;
