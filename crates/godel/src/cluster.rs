//! Scale-out under `mpirun`/`srun` (cargo feature `mpi`, the system's MPI through rsmpi).
//!
//! [`run_jobs`] is the one distribution pattern: jobs `0..n` handed out by a dynamic
//! work queue on rank 0 to whichever rank asks next (rays near the horizon cost more than
//! others, so static stripes would leave ranks idle), results sent back to rank 0, which
//! alone assembles and writes. Rank 0 works too, on a thread of its own, while its main
//! thread serves the queue (only that thread calls MPI: `Threading::Funneled`); with
//! `GODEL_MPI_ROOT_WORKS=0` it only serves (e.g. when rank 0 sits on a service node).
//! The commands bring their own jobs: `godel render` batches of tiles (cmd/render.rs),
//! `godel sequence` whole frames (cmd/sequence.rs); this file knows neither.
//!
//! Failure: a rank whose scene, work or fingerprint fails prints `godel: rank R: <error>`
//! and calls `MPI_Abort`, so the whole job exits non-zero and rank 0 never writes a partial
//! image; a rank that dies is caught by the MPI launcher, which ends the job the same way.

use anyhow::Context;
use mpi::environment::Threading;
use mpi::topology::{Communicator, SimpleCommunicator};
use mpi::traits::{Destination, Source};
use std::sync::mpsc;
use std::sync::Mutex;
use std::time::Duration;

/// Worker → rank 0: "give me a job"; payload: the worker's fingerprint (first time) or
/// the result of its last job (8-byte job number, then the bytes).
const TAG_ASK: i32 = 1;
/// Rank 0 → worker: the next job number, or [`STOP`].
const TAG_JOB: i32 = 2;
const STOP: u64 = u64::MAX;

/// Whether an MPI launcher (OpenMPI's mpirun, Hydra, SLURM's srun with PMI/PMIx) started
/// this process; a plain `godel render` then stays a single, MPI-free process.
pub fn launched_by_mpi() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"]
        .iter()
        .any(|v| std::env::var_os(v).is_some())
}

/// Prints `godel: rank R: <error chain>` and aborts the whole MPI job with main's exit
/// code convention (2 for bad input, 1 otherwise).
pub fn abort(world: &SimpleCommunicator, err: &anyhow::Error) -> ! {
    let chain: Vec<String> = err.chain().map(|c| c.to_string()).collect();
    eprintln!("godel: rank {}: {}", world.rank(), chain.join(": "));
    // As a failed run outside MPI: no output folder of this rank's making left behind.
    datafile::folders::remove_created_folders_left_empty();
    let code = if err
        .chain()
        .any(|c| c.is::<crate::args::UsageError>() || c.is::<scene::SceneError>())
    {
        2
    } else {
        1
    };
    world.abort(code)
}

/// Runs jobs `0..n` over all ranks of `world`. `work` runs on any rank; `done` runs on rank
/// 0 only, once per job, in the order results arrive. `key` must be equal on all ranks (a
/// fingerprint of the input): a rank with another key aborts the job. Errors abort too.
/// Returns, on rank 0, how many jobs each rank ran (empty on the others).
pub fn run_jobs(
    world: &SimpleCommunicator,
    n: usize,
    key: &str,
    work: &(dyn Fn(usize) -> anyhow::Result<Vec<u8>> + Sync),
    done: &mut dyn FnMut(usize, Vec<u8>),
) -> Vec<usize> {
    if world.rank() != 0 {
        worker(world, key, work);
        return vec![];
    }
    let mut per_rank = vec![0; world.size() as usize];
    let next = Mutex::new(0usize);
    let take = || {
        let mut next = next.lock().unwrap_or_else(|e| e.into_inner());
        (*next < n).then(|| {
            *next += 1;
            *next - 1
        })
    };
    let (to_main, results) = mpsc::channel::<(usize, anyhow::Result<Vec<u8>>)>();
    let root_works = std::env::var("GODEL_MPI_ROOT_WORKS").map_or(true, |v| v != "0");
    std::thread::scope(|s| {
        // Rank 0's own worker: takes jobs from the same queue, never calls MPI.
        s.spawn(|| {
            if !root_works {
                return;
            }
            while let Some(job) = take() {
                let failed = {
                    let r = work(job);
                    let failed = r.is_err();
                    let _ = to_main.send((job, r));
                    failed
                };
                if failed {
                    break;
                }
            }
        });
        let mut received = 0;
        let mut workers = world.size() as usize - 1;
        while received < n || workers > 0 {
            let mut idle = true;
            while let Ok((job, result)) = results.try_recv() {
                idle = false;
                match result {
                    Ok(bytes) => {
                        done(job, bytes);
                        per_rank[0] += 1;
                    }
                    Err(e) => abort(world, &e.context(format!("job {job}"))),
                }
                received += 1;
            }
            // Polled, not blocking: a blocking receive spins a core in most MPIs.
            if let Some(status) = world.any_process().immediate_probe_with_tag(TAG_ASK) {
                idle = false;
                let rank = status.source_rank();
                let (msg, _) = world
                    .process_at_rank(rank)
                    .receive_vec_with_tag::<u8>(TAG_ASK);
                match msg
                    .get(..8)
                    .map(|b| u64::from_le_bytes(b.try_into().unwrap()))
                {
                    Some(job) if job != STOP => {
                        done(job as usize, msg[8..].to_vec());
                        received += 1;
                        per_rank[rank as usize] += 1;
                    }
                    _ => {
                        let theirs = String::from_utf8_lossy(msg.get(8..).unwrap_or(&[]));
                        if theirs != key {
                            let e = anyhow::anyhow!(
                                "rank {rank} read a different scene or program version than rank 0 (fingerprint {theirs} ≠ {key})"
                            );
                            abort(world, &e);
                        }
                    }
                }
                let job = take().map_or(STOP, |j| j as u64);
                if job == STOP {
                    workers -= 1;
                }
                world.process_at_rank(rank).send_with_tag(&job, TAG_JOB);
            }
            if idle {
                std::thread::sleep(Duration::from_micros(200));
            }
        }
    });
    per_rank
}

/// A worker rank: asks for jobs until told to stop, sending each result with the next ask.
fn worker(
    world: &SimpleCommunicator,
    key: &str,
    work: &(dyn Fn(usize) -> anyhow::Result<Vec<u8>> + Sync),
) {
    let root = world.process_at_rank(0);
    let mut msg = STOP.to_le_bytes().to_vec();
    msg.extend_from_slice(key.as_bytes());
    loop {
        root.send_with_tag(&msg[..], TAG_ASK);
        let (job, _) = root.receive_with_tag::<u64>(TAG_JOB);
        if job == STOP {
            return;
        }
        match work(job as usize) {
            Ok(bytes) => {
                msg = job.to_le_bytes().to_vec();
                msg.extend_from_slice(&bytes);
            }
            Err(e) => abort(world, &e.context(format!("job {job}"))),
        }
    }
}

/// Starts MPI (funneled: only the main thread calls it).
pub fn start() -> anyhow::Result<mpi::environment::Universe> {
    let (universe, _) = mpi::initialize_with_threading(Threading::Funneled)
        .context("cannot start MPI (already started?)")?;
    Ok(universe)
}
