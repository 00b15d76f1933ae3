//! How many probes the objects have answered (`Target::probe`), counted only with the
//! feature `count-probes` (`examples/probes.rs`, BENCHMARKS.md "Probes a ray"): the work of
//! the intersection search, independent of the machine.

use std::sync::atomic::{AtomicU64, Ordering};

static PROBES: AtomicU64 = AtomicU64::new(0);

/// One probe more.
pub fn add() {
    PROBES.fetch_add(1, Ordering::Relaxed);
}

/// The probes counted since the last call, the count set back to zero.
pub fn take() -> u64 {
    PROBES.swap(0, Ordering::Relaxed)
}
