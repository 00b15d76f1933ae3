//! Contexts on several threads at once (`gpu::context`): each thread's context is its own,
//! and the display EGL shares between them is terminated only with the last one, so a thread
//! that traces after another thread's context is gone traces as before. (The display once
//! went with the first context dropped, and Mesa crashed under the others; then contexts
//! waited for each other, and llvmpipe's compiles, seconds each on one core, ran one by one.)

use crate::common::{bits, example, sized};
use datafile::RayStatus;
use gpu::{GpuTracer, KernelInput};
use render::driver::NoProgress;
use std::sync::mpsc;
use std::sync::{Arc, Barrier};
use std::time::Duration;

/// Far longer than these traces take (a compile of seconds, a frame of 512 samples); a wait
/// past it means the threads wait on each other.
const PATIENCE: Duration = Duration::from_secs(180);

#[test]
fn a_context_traces_while_and_after_another_threads_context_lives() {
    let scene = sized(example("static-sphere"), 64, 8);
    let traced = |tracer: &GpuTracer| -> Vec<Vec<u32>> {
        let records = tracer.trace(&NoProgress).expect("trace").records;
        assert!(
            records.iter().any(|r| r.status == RayStatus::Hit),
            "the ball is seen"
        );
        records.iter().map(bits).collect()
    };
    let alone = traced(&GpuTracer::new(KernelInput::new(&scene)).expect("a context"));

    // The first thread makes its context, the second makes one, traces and drops it while
    // the first still holds its own; then the first traces.
    let turns = Arc::new(Barrier::new(2));
    let (done, results) = mpsc::channel();
    let threads = [true, false].map(|first| {
        let (turns, done, scene) = (turns.clone(), done.clone(), scene.clone());
        std::thread::spawn(move || {
            let input = KernelInput::new(&scene);
            let result = if first {
                let tracer = GpuTracer::new(input).expect("a context");
                turns.wait();
                turns.wait();
                traced(&tracer)
            } else {
                turns.wait();
                let result = traced(&GpuTracer::new(input).expect("a second context"));
                turns.wait();
                result
            };
            done.send((first, result)).expect("the test waits");
        })
    });
    // A thread that panics drops its sender: with both gone the wait below ends at once.
    drop(done);
    for _ in 0..2 {
        let (first, result) = results
            .recv_timeout(PATIENCE)
            .expect("both threads trace: neither waits for the other's context");
        assert!(
            result == alone,
            "the {} thread's records differ from one context's alone",
            if first { "first" } else { "second" }
        );
    }
    for t in threads {
        t.join().expect("the thread ends");
    }
}
