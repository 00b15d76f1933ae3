//! Bounded work: shading requests beyond the workers and the waiting places get 503 (and
//! the cheap routes still answer), those within them wait their turn and are all answered;
//! per-request sizes (lamps, light sources) are capped by the settings checks.

use std::sync::Arc;

use crate::common::{data, error_of, frequency, frequency_settings, get, post, send_to};
use axum::http::StatusCode;
use shade::{Lamp, LightSource, MAX_LAMPS};
use viewer::{ViewerOptions, ViewerState, WorkLimit};

fn viewer_with(work: WorkLimit) -> Arc<ViewerState> {
    let options = ViewerOptions {
        texture_folders: Vec::new(),
        work,
    };
    Arc::new(ViewerState::new_with(std::path::Path::new("api-test.exr"), data(), options).unwrap())
}

#[tokio::test]
async fn requests_beyond_the_limit_get_503() {
    let state = viewer_with(WorkLimit::new(1, 1));
    // Two admitted (one working, one waiting) fill the limit.
    let first = state.work().admit().unwrap();
    let second = state.work().admit().unwrap();
    for route in ["/api/image", "/api/png", "/api/keyframe"] {
        let (status, _, body) = send_to(state.clone(), post(route, &frequency(5000.0))).await;
        assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE, "{route}");
        assert!(error_of(&body).contains("busy"), "{route}");
    }
    // Hovering and the page are not shading work: answered meanwhile.
    for path in ["/api/pixel?col=1&row=1", "/api/info", "/"] {
        let (status, _, _) = send_to(state.clone(), get(path)).await;
        assert_eq!(status, StatusCode::OK, "{path}");
    }
    drop((first, second));
    let (status, _, _) = send_to(state.clone(), post("/api/image", &frequency(5000.0))).await;
    assert_eq!(status, StatusCode::OK);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn requests_within_the_limit_wait_their_turn() {
    // One worker, seven waiting places: eight requests at once are all answered, each with
    // its own picture.
    let state = viewer_with(WorkLimit::new(1, 7));
    let requests: Vec<_> = (0..8)
        .map(|k| {
            let state = state.clone();
            let t = 3000.0 + 500.0 * f64::from(k);
            tokio::spawn(async move { send_to(state, post("/api/image", &frequency(t))).await })
        })
        .collect();
    let mut pictures = Vec::new();
    for r in requests {
        let (status, _, body) = r.await.unwrap();
        assert_eq!(status, StatusCode::OK);
        pictures.push(body);
    }
    pictures.dedup();
    assert_eq!(pictures.len(), 8, "eight temperatures, eight pictures");
    // Every ticket came back.
    let tickets: Vec<_> = (0..8).map(|_| state.work().admit().unwrap()).collect();
    assert!(state.work().admit().is_err());
    drop(tickets);
}

#[test]
fn the_default_limit_follows_the_cores() {
    let cores = std::thread::available_parallelism().unwrap().get();
    let limit = WorkLimit::for_this_machine();
    assert_eq!(limit.workers(), cores);
    assert_eq!(limit.waiting(), 4 * cores);
    // At least one worker whatever is asked.
    assert_eq!(WorkLimit::new(0, 0).workers(), 1);
}

#[tokio::test]
async fn lamps_and_sources_per_request_are_capped() {
    let state = viewer_with(WorkLimit::new(1, 0));
    let lamp = Lamp {
        u: 0.5,
        v: 0.5,
        radius_deg: 5.0,
        period: 1.0,
        phase: 0.0,
        duty: 0.5,
        color: [1.0, 1.0, 0.0],
    };
    // 20,000 lamps cost 21.7 s of both cores for one picture before the cap.
    let mut settings = frequency_settings(5000.0);
    settings.objects.get_mut("ball").unwrap().lamps = vec![lamp.clone(); 20_000];
    let body = serde_json::to_string(&settings).unwrap();
    let (status, _, answer) = send_to(state.clone(), post("/api/image", &body)).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let message = error_of(&answer);
    assert!(message.contains("objects.ball.lamps"), "{message}");
    assert!(
        message.contains(&format!("at most {MAX_LAMPS}")),
        "{message}"
    );

    let mut settings = frequency_settings(5000.0);
    settings.light.sources = vec![
        LightSource {
            on: true,
            intensity: 1.0,
            color: [1.0; 3],
        };
        20_000
    ];
    let body = serde_json::to_string(&settings).unwrap();
    let (status, _, answer) = send_to(state.clone(), post("/api/image", &body)).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(error_of(&answer).contains("light.sources"));
}
