//! The worker threads of a render: rayon's pool with a bounded, checked size, so that a
//! request for a million threads is refused before any work (docs/guide/src/command-line.md, **Limits**).

/// Most worker threads per core: more only adds switching and memory, never speed.
pub const THREADS_PER_CORE: usize = 8;

/// The cores this process may use (affinity and cgroup quotas included; 1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Checks a thread count: at least 1, at most [`THREADS_PER_CORE`] per core; the message
/// names no flag (the caller does).
pub fn check_threads(n: usize) -> Result<usize, String> {
    let cores = cores();
    let max = THREADS_PER_CORE * cores;
    if n == 0 {
        return Err("must be at least 1".into());
    }
    if n > max {
        return Err(format!(
            "at most {max} ({THREADS_PER_CORE} per core; this machine gives {cores} core(s)), got {n}"
        ));
    }
    Ok(n)
}

/// Why no pool was made.
#[derive(Debug, thiserror::Error)]
pub enum ThreadsError {
    /// The count asked for is out of bounds (see [`check_threads`]).
    #[error("{0}")]
    Count(String),
    #[error("cannot start worker threads: {0}")]
    Start(#[from] rayon::ThreadPoolBuildError),
}

/// The pool of `wanted` worker threads (checked), or one per core.
pub fn thread_pool(wanted: Option<usize>) -> Result<rayon::ThreadPool, ThreadsError> {
    let n = match wanted {
        Some(n) => check_threads(n).map_err(ThreadsError::Count)?,
        None => 0, // rayon's default: one per core
    };
    Ok(rayon::ThreadPoolBuilder::new().num_threads(n).build()?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thread_counts_are_bounded_by_the_cores() {
        let max = THREADS_PER_CORE * cores();
        assert_eq!(check_threads(1).unwrap(), 1);
        assert_eq!(check_threads(max).unwrap(), max);
        for bad in [0, max + 1, 100_000] {
            assert!(check_threads(bad).is_err());
            assert!(matches!(
                thread_pool(Some(bad)),
                Err(ThreadsError::Count(_))
            ));
        }
        assert_eq!(thread_pool(Some(2)).unwrap().current_num_threads(), 2);
    }
}
