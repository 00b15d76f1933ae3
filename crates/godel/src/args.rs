//! Validation of raw command-line values shared by the subcommands: comma-separated vectors,
//! finite and bounded numbers, thread counts, output formats. Every failure is a
//! [`UsageError`] naming the flag, which `main` turns into exit code 2.

use anyhow::Context;
use clap::ValueEnum;
use scene::Scene;
use std::fmt;
use std::path::PathBuf;

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
/// ([`scene::A_RANGE`]).
pub fn scale_a(flag: &str, a: f64) -> anyhow::Result<f64> {
    let a = positive(flag, a)?;
    let (lo, hi) = scene::A_RANGE;
    if !(lo..=hi).contains(&a) {
        return Err(usage(
            flag,
            format!(
                "{} is outside [{lo:e}, {hi:e}], as in scenes (spacetime.a): the metric loses \
                 the precision of f64 there",
                scene::short(a)
            ),
        ));
    }
    Ok(a)
}

/// Checks the coordinates of an event or position given with `flag` (named `names`, e.g.
/// `t`, `R`, `phi`, `z`): each within ±[`scene::MAX_COORDINATE_PER_A`]·a as in scenes (an
/// angle within ±that number of radians).
pub fn coordinates(flag: &str, names: &[&str], values: &[f64], a: f64) -> anyhow::Result<()> {
    for (name, &v) in names.iter().zip(values) {
        let bound = match *name {
            "phi" => scene::MAX_COORDINATE_PER_A,
            _ => scene::MAX_COORDINATE_PER_A * a,
        };
        if v.abs() > bound {
            return Err(usage(
                flag,
                format!(
                    "{name} = {} is beyond ±{bound:e}, as in scenes (1e6 times the scale a): \
                     the tracer loses precision there",
                    scene::short(v)
                ),
            ));
        }
    }
    Ok(())
}

/// Most worker threads per core: more only adds switching and memory, never speed.
pub const THREADS_PER_CORE: usize = 8;

/// The cores this process may use (affinity and cgroup quotas included; 1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Checks a `--threads` value: at least 1, at most [`THREADS_PER_CORE`] per core.
pub fn threads(flag: &str, n: usize) -> anyhow::Result<usize> {
    let cores = cores();
    let max = THREADS_PER_CORE * cores;
    if n == 0 {
        return Err(usage(flag, "must be at least 1"));
    }
    if n > max {
        return Err(usage(
            flag,
            format!(
                "at most {max} ({THREADS_PER_CORE} per core; this machine gives {cores} core(s)), got {n}"
            ),
        ));
    }
    Ok(n)
}

/// Loads the scene named on the command line, or the built-in one.
pub fn load_scene(path: &Option<PathBuf>) -> anyhow::Result<Scene> {
    Ok(match path {
        Some(p) => Scene::from_file(p)?,
        None => Scene::builtin(),
    })
}

/// The worker thread pool of `--threads` (checked: 1 to 8 per core).
pub fn thread_pool(wanted: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let n = match wanted {
        Some(n) => threads("--threads", n)?,
        None => 0, // rayon's default: one per core
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .context("cannot start worker threads")
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
    fn thread_counts_are_bounded_by_the_cores() {
        let max = THREADS_PER_CORE * cores();
        assert_eq!(threads("--threads", 1).unwrap(), 1);
        assert_eq!(threads("--threads", max).unwrap(), max);
        for bad in [0, max + 1, 100_000] {
            let e = threads("--threads", bad).unwrap_err();
            assert!(e.to_string().starts_with("--threads: "), "{e}");
        }
    }

    #[test]
    fn the_scale_and_coordinates_have_the_ranges_of_scenes() {
        assert_eq!(scale_a("--a", 2.0).unwrap(), 2.0);
        for bad in [1e-300, 1e300, 0.0, -1.0] {
            let e = scale_a("--a", bad).unwrap_err().to_string();
            assert!(e.starts_with("--a: ") && e.len() < 200, "{e}");
        }
        let names = ["t", "R", "phi", "z"];
        coordinates("--at", &names, &[1e6, 0.5, -1e6, 0.0], 1.0).unwrap();
        let e = coordinates("--at", &names, &[1e300, 0.0, 0.0, 0.0], 1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--at: t = 1e300 is beyond ±1e6, as in scenes (1e6 times the scale a): the tracer \
             loses precision there"
        );
        assert!(coordinates("--at", &names, &[0.0, 0.0, 2e6, 0.0], 1.0).is_err());
        // Lengths scale with a; angles do not.
        coordinates("--at", &names, &[0.0, 0.0, 0.0, 5e6], 10.0).unwrap();
        assert!(coordinates("--at", &names, &[0.0, 0.0, 2e6, 0.0], 10.0).is_err());
    }

    #[test]
    fn positive_rejects_zero_negative_and_nan() {
        assert_eq!(positive("--a", 2.0).unwrap(), 2.0);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(positive("--a", bad).is_err());
        }
    }
}
