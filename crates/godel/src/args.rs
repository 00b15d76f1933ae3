//! Validation of raw command-line values shared by the subcommands: comma-separated vectors,
//! finite and bounded numbers, thread counts, output formats. Every failure is a
//! [`UsageError`] naming the flag, which `main` turns into exit code 2.

use clap::ValueEnum;
use std::fmt;

/// The output formats of `godel geodesic` and `godel connect` (`--format`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    Csv,
    Json,
}

/// An invalid command-line value: `--flag: what is wrong`.
#[derive(Debug, Clone, PartialEq)]
pub struct UsageError {
    pub flag: String,
    pub message: String,
}

impl fmt::Display for UsageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.flag, self.message)
    }
}

impl std::error::Error for UsageError {}

/// A [`UsageError`] for `flag` as an `anyhow::Error`.
pub fn usage(flag: &str, message: impl Into<String>) -> anyhow::Error {
    UsageError {
        flag: flag.to_string(),
        message: message.into(),
    }
    .into()
}

/// Parses `N` comma-separated finite numbers, e.g. `--at 0,1.5,0,0`.
pub fn parse_vector<const N: usize>(flag: &str, text: &str) -> anyhow::Result<[f64; N]> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != N {
        return Err(usage(
            flag,
            format!(
                "expected {N} comma-separated numbers, got {} in '{text}'",
                parts.len()
            ),
        ));
    }
    let mut out = [0.0; N];
    for (i, part) in parts.iter().enumerate() {
        let v: f64 = part
            .parse()
            .map_err(|_| usage(flag, format!("'{part}' is not a number")))?;
        if !v.is_finite() {
            return Err(usage(
                flag,
                format!("component {} must be finite, got {part}", i + 1),
            ));
        }
        out[i] = v;
    }
    Ok(out)
}

/// Parses 1 to `most` comma-separated finite numbers, e.g. `--members 0,2,4.5`.
pub fn parse_list(flag: &str, text: &str, most: usize) -> anyhow::Result<Vec<f64>> {
    let mut out = Vec::new();
    for part in text.split(',').map(str::trim) {
        let v: f64 = part
            .parse()
            .map_err(|_| usage(flag, format!("'{part}' is not a number")))?;
        if !v.is_finite() {
            return Err(usage(flag, format!("{part} is not finite")));
        }
        out.push(v);
    }
    if out.len() > most {
        return Err(usage(
            flag,
            format!("at most {most} numbers, got {} in '{text}'", out.len()),
        ));
    }
    Ok(out)
}

/// Checks that `v` is finite and strictly positive.
pub fn positive(flag: &str, v: f64) -> anyhow::Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(usage(
            flag,
            format!("must be positive and finite, got {}", scene::short(v)),
        ))
    }
}

/// Checks the Gödel parameter `--a`: positive, within the range scenes allow
/// (`scene::ranges`).
pub fn scale_a(flag: &str, a: f64) -> anyhow::Result<f64> {
    scene::ranges::check_a(a).map_err(|e| usage(flag, e))
}

/// The Gödel-type member of `--m2` and `--omega` (both required), each checked in the
/// ranges scenes allow (`scene::ranges`).
pub fn member(m2: Option<f64>, omega: Option<f64>) -> anyhow::Result<spacetime::GodelType> {
    let need = "needed by --metric godel-type (with --m2 and --omega)";
    let omega = omega.ok_or_else(|| usage("--omega", need))?;
    let omega = scene::ranges::check_omega(omega).map_err(|e| usage("--omega", e))?;
    let m2 = m2.ok_or_else(|| usage("--m2", need))?;
    let m2 = scene::ranges::check_m2(m2, omega).map_err(|e| usage("--m2", e))?;
    Ok(spacetime::GodelType::new(m2, omega))
}

/// Checks the coordinates of an event or position given with `flag` (named `names`, e.g.
/// `t`, `R`, `phi`, `z`): each within ±1e6·a as in scenes (`scene::ranges`).
pub fn coordinates(flag: &str, names: &[&str], values: &[f64], a: f64) -> anyhow::Result<()> {
    scene::ranges::check_coordinates(names, values, a).map_err(|e| usage(flag, e))
}

/// The worker thread pool of `--threads` (checked: 1 to 8 per core).
pub fn thread_pool(wanted: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    use render::threads::ThreadsError;
    render::threads::thread_pool(wanted).map_err(|e| match e {
        ThreadsError::Count(message) => usage("--threads", message),
        e => e.into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors_parse_and_reject_bad_input() {
        assert_eq!(
            parse_vector::<3>("--dir", "1, -2,3e-1").unwrap(),
            [1.0, -2.0, 0.3]
        );
        for bad in ["1,2", "1,2,3,4", "1,x,3", "1,NaN,3", "inf,0,0", ""] {
            let e = parse_vector::<3>("--dir", bad).unwrap_err();
            assert!(e.to_string().starts_with("--dir: "), "{e}");
            assert!(e.is::<UsageError>());
        }
    }

    #[test]
    fn thread_counts_name_the_flag() {
        let max = render::threads::THREADS_PER_CORE * render::threads::cores();
        assert_eq!(thread_pool(Some(max)).unwrap().current_num_threads(), max);
        for bad in [0, max + 1] {
            let e = thread_pool(Some(bad)).unwrap_err();
            assert!(e.to_string().starts_with("--threads: "), "{e}");
            assert!(e.is::<UsageError>());
        }
    }

    #[test]
    fn the_ranges_of_scenes_name_the_flag() {
        assert_eq!(scale_a("--a", 2.0).unwrap(), 2.0);
        let e = scale_a("--a", 1e-300).unwrap_err();
        assert!(e.to_string().starts_with("--a: 1e-300 is outside"), "{e}");
        assert!(e.is::<UsageError>());
        let e = coordinates("--at", &["t", "R"], &[1e300, 0.0], 1.0).unwrap_err();
        assert!(
            e.to_string().starts_with("--at: t = 1e300 is beyond"),
            "{e}"
        );
    }

    #[test]
    fn positive_rejects_zero_negative_and_nan() {
        assert_eq!(positive("--a", 2.0).unwrap(), 2.0);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(positive("--a", bad).is_err());
        }
    }
}
