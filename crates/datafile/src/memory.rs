//! Sizing work against memory before it starts: what a command will hold at its peak,
//! estimated from its pixel count ([`record_bytes`]), is compared with a budget of what the
//! system has available now ([`budget`]), and work that would not fit is refused (the
//! caller names the flag, field or argument that sets its size), instead of swapping or
//! being killed halfway: `godel render`, `look`, `explore` and the Python module's `render`.
//! The other limits (pixels, rays, sides) stay as they are; this one depends on the machine.

/// Bytes one record takes in memory ([`crate::PixelRecord`]) with `lights` light planes.
pub fn record_bytes(lights: usize) -> u64 {
    (std::mem::size_of::<crate::PixelRecord>() + 4 * lights) as u64
}

/// Bytes per ray at the peak of writing a data file of `lights` light planes: its records,
/// the channel planes and the encoded bytes (one 4-byte value per channel each), the
/// preview's RGB. Measured: 200 bytes per ray for `godel render` and `godel look` of
/// 8·10⁶ rays without lights (BENCHMARKS.md, "Memory of look, of the viewer's look pictures,
/// and of explore"); three records' worth is a little more.
pub fn writing_bytes(lights: usize) -> u64 {
    3 * record_bytes(lights)
}

/// What a run writing a data file of `rays` rays with `lights` light planes needs, refused
/// as [`check`] does (the work `what`).
pub fn check_writing(what: &str, rays: u64, lights: usize) -> Result<(), String> {
    check(what, rays.saturating_mul(writing_bytes(lights)), None)
}

/// What the work may use: `GODEL_MEMORY_BUDGET` (bytes, e.g. `8e9`) where set — a job under
/// a memory limit that `/proc/meminfo` does not show (a cgroup) says so there —, else three
/// quarters of the memory the system has available now (Linux's `MemAvailable`, which counts
/// reclaimable caches), or 4 GiB where that is unknown. A variable set to anything but a
/// number of bytes from 0 to [`MOST_BUDGET`] is refused (a message naming it), never ignored:
/// a typo would otherwise size the work by a budget the user did not ask for. Empty is unset.
pub fn budget() -> Result<u64, BadBudget> {
    let Some(text) = std::env::var_os(BUDGET_VARIABLE).filter(|v| !v.is_empty()) else {
        return Ok(available().map_or(4 << 30, |bytes| bytes / 4 * 3));
    };
    let shown = text.to_string_lossy();
    text.to_str()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|b| (0.0..=MOST_BUDGET).contains(b))
        .map(|b| b as u64)
        .ok_or_else(|| BadBudget {
            reason: format!(
                "must be a number of bytes from 0 to {MOST_BUDGET:e} (e.g. 8e9), got {shown:?}"
            ),
        })
}

/// A [`BUDGET_VARIABLE`] that is not a budget: displayed as `GODEL_MEMORY_BUDGET: reason`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BadBudget {
    pub reason: String,
}

impl std::fmt::Display for BadBudget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{BUDGET_VARIABLE}: {}", self.reason)
    }
}

impl std::error::Error for BadBudget {}

/// The largest budget [`BUDGET_VARIABLE`] may set, in bytes (an exabyte): more is a typo.
pub const MOST_BUDGET: f64 = 1e18;

/// The environment variable that sets the [`budget`].
pub const BUDGET_VARIABLE: &str = "GODEL_MEMORY_BUDGET";

/// `MemAvailable` of /proc/meminfo, in bytes.
fn available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Refuses work that needs `needed` bytes when the [`budget`] is less, saying what the work
/// is (`what`) and, when given, what would fit (`fits`); refuses a bad [`BUDGET_VARIABLE`].
pub fn check(what: &str, needed: u64, fits: Option<String>) -> Result<(), String> {
    let budget = budget().map_err(|e| e.to_string())?;
    if needed <= budget {
        return Ok(());
    }
    let hint = fits.map(|f| format!("; {f} fits")).unwrap_or_default();
    Err(format!(
        "{what} needs about {} of memory, more than the budget of {} (three quarters of what \
         this machine has available now, or {BUDGET_VARIABLE}){hint}",
        bytes(needed),
        bytes(budget)
    ))
}

/// `b` bytes for a message: `2.6 GB`, `340 MB`, `1.2 MB`, `20 kB`.
fn bytes(b: u64) -> String {
    match b as f64 {
        b if b >= 1e9 => format!("{:.1} GB", b / 1e9),
        b if b >= 1e7 => format!("{:.0} MB", b / 1e6),
        b if b >= 1e6 => format!("{:.1} MB", b / 1e6),
        b => format!("{:.0} kB", b / 1e3),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_beyond_the_budget_is_refused() {
        check("a picture", 1 << 20, None).unwrap();
        let text = check("a picture", u64::MAX, Some("--width 100".into())).unwrap_err();
        assert!(text.starts_with("a picture needs about"), "{text}");
        assert!(text.ends_with("; --width 100 fits"), "{text}");
        assert!(record_bytes(2) > record_bytes(0));
        assert_eq!(bytes(2_600_000_000), "2.6 GB");
        assert_eq!(bytes(340_000_000), "340 MB");
        assert_eq!(bytes(1_234_567), "1.2 MB");
        assert_eq!(bytes(20_000), "20 kB");
    }
}
