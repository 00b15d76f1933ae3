//! Many picture requests at once against the viewer's routes (in-process, no sockets): how
//! many are answered or turned away (503), and the process's peak memory. Without a bound on
//! concurrent shading every request held its own picture buffers at once.
//! `cargo run -p viewer --example concurrent_requests -- 4000 2000 200 [WORKERS]`
//! (width, height of the synthetic data file, number of simultaneous requests; WORKERS
//! replaces the default bound, one per core, by that many workers and no waiting places:
//! 200 shows the unbounded server).

#[path = "../benches/common/mod.rs"]
mod common;

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

use axum::body::Body;
use axum::http::Request;
use http_body_util::BodyExt;
use shade::ShaderKind;
use tower::ServiceExt;
use viewer::{Access, ViewerOptions, ViewerState, WorkLimit};

/// A field of /proc/self/status in MiB (e.g. `VmHWM`, the peak resident memory).
fn status_mib(field: &str) -> f64 {
    let text = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    text.lines()
        .find_map(|l| l.strip_prefix(field)?.strip_prefix(':'))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("numbers: WIDTH HEIGHT REQUESTS"))
        .collect();
    let (width, height, requests, workers) = match args[..] {
        [w, h, r] => (w, h, r, None),
        [w, h, r, k] => (w, h, r, Some(k)),
        _ => panic!("usage: concurrent_requests WIDTH HEIGHT REQUESTS [WORKERS]"),
    };
    let mut options = ViewerOptions::default();
    if let Some(k) = workers {
        options.work = WorkLimit::new(k, 0);
    }
    let state = Arc::new(
        ViewerState::new_with(Path::new("bench.exr"), common::data(width, height), options)
            .expect("loads"),
    );
    println!(
        "{} workers, {} waiting places",
        state.work().workers(),
        state.work().waiting()
    );
    let mut settings = state.info().defaults;
    settings.shaders = vec![ShaderKind::Texture];
    let body = serde_json::to_string(&settings).expect("settings serialize");
    let router = viewer::router(state.clone(), Access::local(8737));
    println!(
        "{width}×{height}, {requests} requests at once; loaded: RSS {:.0} MiB",
        status_mib("VmRSS")
    );
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .expect("runtime");
    let statuses = runtime.block_on(async {
        let tasks: Vec<_> = (0..requests)
            .map(|_| {
                let request = Request::post("/api/image")
                    .header("host", "127.0.0.1:8737")
                    .header("content-type", "application/json")
                    .body(Body::from(body.clone()))
                    .expect("request");
                let router = router.clone();
                tokio::spawn(async move {
                    let response = router.oneshot(request).await.expect("answered");
                    let status = response.status().as_u16();
                    let _ = response.into_body().collect().await;
                    status
                })
            })
            .collect();
        let mut counts = BTreeMap::new();
        for t in tasks {
            *counts.entry(t.await.expect("task")).or_insert(0usize) += 1;
        }
        counts
    });
    println!("statuses: {statuses:?}");
    println!(
        "peak RSS (VmHWM) {:.0} MiB, RSS after {:.0} MiB",
        status_mib("VmHWM"),
        status_mib("VmRSS")
    );
}
