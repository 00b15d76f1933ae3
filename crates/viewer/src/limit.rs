//! [`WorkLimit`]: a bound on the shading work the server does at once. Each shading request
//! is first admitted ([`WorkLimit::admit`]: at most `workers + waiting` at a time, else 503),
//! then waits for one of `workers` slots and shades on a blocking thread
//! ([`Ticket::run`]). Memory is so bounded by the admitted requests (their bodies) and the
//! running ones (their pictures): without it, 200 concurrent requests on a 4000×2000 file
//! reached 6.6 GB. A job whose client went away keeps its slots until it ends, so the count
//! is of real work.

use std::num::NonZeroUsize;
use std::sync::Arc;

use axum::http::StatusCode;
use tokio::sync::{OwnedSemaphorePermit, Semaphore};

use crate::api_error::ApiError;

/// How many requests may wait for a slot, per slot, by default.
const WAITING_PER_WORKER: usize = 4;

/// Slots for shading work, and admission to them. A clone shares them (explore mode's
/// frames share the server's bound).
#[derive(Clone, Debug)]
pub struct WorkLimit {
    /// What the jobs are, for the busy answer ("pictures being shaded").
    work: &'static str,
    workers: usize,
    waiting: usize,
    admitted: Arc<Semaphore>,
    running: Arc<Semaphore>,
}

/// One admitted request: holds its admission until its job has run.
#[derive(Debug)]
pub struct Ticket {
    admitted: OwnedSemaphorePermit,
    running: Arc<Semaphore>,
}

impl WorkLimit {
    /// `workers` jobs at once (at least 1), `waiting` more admitted to wait for them.
    pub fn new(workers: usize, waiting: usize) -> WorkLimit {
        WorkLimit::of("pictures being shaded", workers, waiting)
    }

    /// [`WorkLimit::new`] for jobs that `work` names in the busy answer (a plural: "recordings
    /// being made into scripts").
    pub fn of(work: &'static str, workers: usize, waiting: usize) -> WorkLimit {
        let workers = workers.max(1);
        WorkLimit {
            work,
            workers,
            waiting,
            admitted: Arc::new(Semaphore::new(workers + waiting)),
            running: Arc::new(Semaphore::new(workers)),
        }
    }

    /// One worker per core, four waiting per worker.
    pub fn for_this_machine() -> WorkLimit {
        let cores = std::thread::available_parallelism().map_or(1, NonZeroUsize::get);
        WorkLimit::new(cores, WAITING_PER_WORKER * cores)
    }

    pub fn workers(&self) -> usize {
        self.workers
    }

    pub fn waiting(&self) -> usize {
        self.waiting
    }

    /// Admits one request, or answers 503 when `workers + waiting` are already admitted.
    pub fn admit(&self) -> Result<Ticket, ApiError> {
        let admitted = self.admitted.clone().try_acquire_owned().map_err(|_| {
            ApiError::new(
                StatusCode::SERVICE_UNAVAILABLE,
                format!(
                    "the viewer is busy ({} {}, {} waiting): try again",
                    self.workers, self.work, self.waiting
                ),
            )
        })?;
        Ok(Ticket {
            admitted,
            running: self.running.clone(),
        })
    }
}

impl Ticket {
    /// Waits for a slot, then runs `job` on a blocking thread; a panic there (a bug, never
    /// input) becomes a 500.
    pub async fn run<T: Send + 'static>(
        self,
        job: impl FnOnce() -> T + Send + 'static,
    ) -> Result<T, ApiError> {
        let slot = self
            .running
            .clone()
            .acquire_owned()
            .await
            .map_err(|e| ApiError::internal(format!("shading slots closed: {e}")))?;
        let admitted = self.admitted;
        tokio::task::spawn_blocking(move || {
            let result = job();
            drop((slot, admitted));
            result
        })
        .await
        .map_err(|e| ApiError::internal(format!("shading failed: {e}")))
    }
}
