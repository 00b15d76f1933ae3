//! Running fuzz cases: how many (`GODEL_FUZZ_CASES`), from which seed (`GODEL_FUZZ_SEED`),
//! which one alone (`GODEL_FUZZ_CASE`), each on a worker thread under a time limit
//! (`GODEL_FUZZ_LIMIT_S`) with panics caught; a test stops after 5 failing cases
//! (`GODEL_FUZZ_MAX_FAILURES` collects more). A case that panics, breaks a checked promise
//! or runs past the limit fails the test with the case printed and the command that
//! replays it. A worker past the limit cannot be stopped, so the test fails at once.

use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::gen::{mix, Gen};

/// The seed when `GODEL_FUZZ_SEED` is not set.
pub const DEFAULT_SEED: u64 = 20_100_410;
/// Cases over all fuzz tests when `GODEL_FUZZ_CASES` is not set.
pub const DEFAULT_CASES: u64 = 20_000;
/// Per-case time limit when `GODEL_FUZZ_LIMIT_S` is not set: the slowest cases (a far
/// free-fall worldline, up to 400,000 integrator steps) took up to 6.4 s on the 2-core
/// machine under load ~10 (BENCHMARKS.md, "Fuzzing"); a hang never ends.
pub const DEFAULT_LIMIT: Duration = Duration::from_secs(30);
/// Failures (other than a time-out) collected before the test stops, when
/// `GODEL_FUZZ_MAX_FAILURES` is not set.
const MAX_FAILURES: u64 = 5;

fn env_u64(name: &str) -> Option<u64> {
    let v = std::env::var(name).ok()?;
    let v = v.trim();
    let parsed = match v.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => v.parse(),
    };
    Some(parsed.unwrap_or_else(|_| panic!("{name}={v:?} is not a non-negative integer")))
}

/// One fuzz test's run: its cases, outcomes and failures.
pub struct Fuzz {
    test: &'static str,
    seed: u64,
    cases: u64,
    only: Option<u64>,
    limit: Duration,
    max_failures: u64,
    outcomes: BTreeMap<String, u64>,
    failures: Vec<String>,
    slowest: Vec<(Duration, u64)>,
    started: Instant,
}

impl Fuzz {
    /// The run of test `test` (its function name, for the replay command), which takes
    /// `share` of all cases.
    pub fn new(test: &'static str, share: f64) -> Fuzz {
        let seed = env_u64("GODEL_FUZZ_SEED").unwrap_or(DEFAULT_SEED);
        let total = env_u64("GODEL_FUZZ_CASES").unwrap_or(DEFAULT_CASES);
        let limit = std::env::var("GODEL_FUZZ_LIMIT_S")
            .ok()
            .and_then(|v| v.trim().parse::<f64>().ok())
            .filter(|s| s.is_finite() && *s > 0.0)
            .map(Duration::from_secs_f64)
            .unwrap_or(DEFAULT_LIMIT);
        let cases = ((total as f64 * share).ceil() as u64).max(1);
        let only = env_u64("GODEL_FUZZ_CASE");
        eprintln!(
            "{test}: seed {seed} (GODEL_FUZZ_SEED), {cases} cases (GODEL_FUZZ_CASES={total} over all tests), limit {limit:?} per case{}",
            only.map(|k| format!(", only case {k} (GODEL_FUZZ_CASE)")).unwrap_or_default()
        );
        Fuzz {
            test,
            seed,
            cases,
            only,
            limit,
            max_failures: env_u64("GODEL_FUZZ_MAX_FAILURES")
                .unwrap_or(MAX_FAILURES)
                .max(1),
            outcomes: BTreeMap::new(),
            failures: Vec::new(),
            slowest: Vec::new(),
            started: Instant::now(),
        }
    }

    /// The indices of the cases to run.
    pub fn indices(&self) -> Vec<u64> {
        match self.only {
            Some(k) => vec![k],
            None => (0..self.cases).collect(),
        }
    }

    /// The random source of case `index` (the same for the same seed, test and index).
    pub fn gen(&self, index: u64) -> Gen {
        let name = self.test.bytes().fold(0u64, |h, b| mix(h ^ u64::from(b)));
        Gen::new(mix(self.seed ^ name) ^ index)
    }

    /// Whether a sampled extra check (e.g. the command line) runs for case `index`: about
    /// one case in `every`, and always when a case is replayed alone.
    pub fn sampled(&self, index: u64, every: u64) -> bool {
        self.only.is_some() || mix(index ^ 0x5eed).is_multiple_of(every)
    }

    fn replay(&self, index: u64) -> String {
        format!(
            "GODEL_FUZZ_SEED={} GODEL_FUZZ_CASE={index} cargo test -p godel --test fuzz {}",
            self.seed, self.test
        )
    }

    /// Runs `case` (described by `shown`) on a worker thread under the time limit. `Ok`
    /// names the outcome (counted for the summary); `Err` is a broken promise.
    pub fn run<F>(&mut self, index: u64, shown: &str, case: F)
    where
        F: FnOnce() -> Result<String, String> + Send + 'static,
    {
        if self.only.is_some() {
            eprintln!("--- case {index} ---\n{shown}\n--- end of case ---");
        }
        let (tx, rx) = mpsc::channel();
        let started = Instant::now();
        std::thread::Builder::new()
            .name(format!("{}-{index}", self.test))
            .spawn(move || {
                let result = catch_unwind(AssertUnwindSafe(case)).map_err(|p| {
                    p.downcast_ref::<String>()
                        .cloned()
                        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                        .unwrap_or_else(|| "a panic".into())
                });
                let _ = tx.send(result);
            })
            .expect("start a worker thread");
        let result = rx.recv_timeout(self.limit);
        let took = started.elapsed();
        let problem = match result {
            Err(_) => {
                // The worker cannot be stopped: fail now, with the case.
                panic!(
                    "{}: case {index} did not finish within {:?} (a hang or unbounded work)\n\
                     replay: {}\n--- case ---\n{shown}\n--- end of case ---",
                    self.test,
                    self.limit,
                    self.replay(index)
                );
            }
            Ok(Err(panic)) => format!("panicked: {panic}"),
            Ok(Ok(Err(broken))) => broken,
            Ok(Ok(Ok(outcome))) => {
                if self.only.is_some() {
                    eprintln!("case {index}: {outcome} in {took:?}");
                }
                *self.outcomes.entry(outcome).or_default() += 1;
                self.slowest.push((took, index));
                self.slowest.sort_by(|a, b| b.cmp(a));
                self.slowest.truncate(3);
                return;
            }
        };
        self.failures.push(format!(
            "case {index}: {problem}\nreplay: {}\n--- case ---\n{shown}\n--- end of case ---",
            self.replay(index)
        ));
        if self.failures.len() as u64 >= self.max_failures {
            self.finish();
        }
    }

    /// Prints the summary; fails the test if any case failed.
    pub fn finish(&mut self) {
        let slowest: Vec<String> = self
            .slowest
            .iter()
            .map(|(d, k)| format!("case {k} {:.0} ms", d.as_secs_f64() * 1e3))
            .collect();
        eprintln!(
            "{}: {} cases in {:.1} s; outcomes {:?}; slowest: {}",
            self.test,
            self.outcomes.values().sum::<u64>() + self.failures.len() as u64,
            self.started.elapsed().as_secs_f64(),
            self.outcomes,
            slowest.join(", ")
        );
        if !self.failures.is_empty() {
            panic!(
                "{}: {} failing case(s)\n\n{}",
                self.test,
                self.failures.len(),
                self.failures.join("\n\n")
            );
        }
    }
}
