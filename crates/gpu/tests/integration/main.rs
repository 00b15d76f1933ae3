//! The gpu crate's integration tests, one binary (the crate is linked once, not once per
//! file). One module: `cargo test -p gpu --test integration rounds`. The kernel on Mesa's
//! llvmpipe (and softpipe, in a process of its own: `agreement_on_softpipe`) against the CPU
//! exact tracer, its pieces against their Rust twins, its rules, and every variant through
//! glslang.

mod common;

mod agreement;
// Named to run early (libtest starts tests in the order of their names): softpipe traces on
// one core, in a process of its own, beside the llvmpipe tests, not alone at the end.
mod agreement_on_softpipe;
mod check;
mod family;
mod faults;
mod glslang;
mod kept_probes;
mod kernel_rules;
mod probes;
mod rounds;
mod table;
mod threads;
