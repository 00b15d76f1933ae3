//! Sizing work against memory before it starts (`datafile::memory`), a refusal named as a
//! usage error by the flag or field that sets the work's size, or by `GODEL_MEMORY_BUDGET`
//! where that variable is not a budget.

use crate::args::usage;
pub use datafile::memory::record_bytes;
use datafile::memory::BUDGET_VARIABLE;

/// The memory budget (`datafile::memory::budget`); a bad `GODEL_MEMORY_BUDGET` is a usage
/// error naming the variable.
pub fn budget() -> anyhow::Result<u64> {
    datafile::memory::budget().map_err(|e| usage(BUDGET_VARIABLE, e.reason))
}

/// What a run writing a data file of `rays` rays with `lights` light planes needs; refused
/// as a usage error naming `flag`, the work `what`.
pub fn check_writing(flag: &str, what: &str, rays: u64, lights: usize) -> anyhow::Result<()> {
    budget()?;
    datafile::memory::check_writing(what, rays, lights).map_err(|e| usage(flag, e))
}

/// Refuses work that needs `needed` bytes beyond the budget: a usage error naming `flag`,
/// saying what the work is (`what`) and, when given, what would fit (`fits`).
pub fn check(flag: &str, what: &str, needed: u64, fits: Option<String>) -> anyhow::Result<()> {
    budget()?;
    datafile::memory::check(what, needed, fits).map_err(|e| usage(flag, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_beyond_the_budget_names_the_flag() {
        check("--width", "a picture", 1 << 20, None).unwrap();
        let e = check("--width", "a picture", u64::MAX, None).unwrap_err();
        assert!(
            e.to_string().starts_with("--width: a picture needs about"),
            "{e}"
        );
        assert!(e.is::<crate::args::UsageError>());
    }
}
