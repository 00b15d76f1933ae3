//! Explore mode's progression and cancellation (`viewer::explore`), with a frame source whose
//! frames say which event and level they were made for (t_emit = −t, g = 1 coarse, 2 full)
//! and whose work can be held at a gate, and its routes (`viewer::explore_routes`).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use axum::body::Body;
use axum::http::{Request, StatusCode};
use datafile::record::RayStatus;
use datafile::{DataFile, PixelRecord};
use http_body_util::BodyExt;
use render::map::{LightRay, Map, MapPoint};
use tower::ServiceExt;
use viewer::explore::{Explorer, FrameSource, Level, ObserverEvent};
use viewer::kernel_routes::KernelInput;
use viewer::page_check::{CheckedSample, Verdict, MAX_CHECK_BYTES, MAX_CHECK_SAMPLES};
use viewer::view::{Velocity, View};
use viewer::wire::{read_header, split_sequence, SampleType, HEADER_LEN};
use viewer::Access;

use crate::common;

const FULL: (usize, usize) = (common::WIDTH, common::HEIGHT);
const COARSE: (usize, usize) = (2, 1);

/// The frame source of these tests. Work on an event whose time is in `held` waits (at most
/// ten seconds) until the gate opens or its cancel flag is set, and then returns its frame
/// anyway, as a source that ignores cancelling would.
#[derive(Clone, Default)]
struct Fake {
    /// (t, level) of each frame begun, in order.
    begun: Arc<Mutex<Vec<(f64, Level)>>>,
    held: Arc<Mutex<Vec<(f64, Level)>>>,
    gate: Arc<AtomicBool>,
}

impl Fake {
    fn begun(&self) -> Vec<(f64, Level)> {
        self.begun.lock().unwrap().clone()
    }
}

fn event(t: f64) -> ObserverEvent {
    ObserverEvent {
        t,
        x: 0.0,
        y: 0.0,
        z: 0.0,
    }
}

impl FrameSource for Fake {
    fn start(&self) -> ObserverEvent {
        event(0.0)
    }
    fn bound(&self) -> f64 {
        100.0
    }
    fn frame(
        &self,
        event: ObserverEvent,
        level: Level,
        cancel: &AtomicBool,
    ) -> Result<Option<DataFile>, String> {
        self.begun.lock().unwrap().push((event.t, level));
        if self.held.lock().unwrap().contains(&(event.t, level)) {
            for _ in 0..10_000 {
                if self.gate.load(Ordering::SeqCst) || cancel.load(Ordering::SeqCst) {
                    break;
                }
                std::thread::sleep(Duration::from_millis(1));
            }
        }
        let ((w, h), g) = match level {
            Level::Coarse => (COARSE, 1.0),
            Level::Full => (FULL, 2.0),
        };
        let record = testkit::hit(0, 0.5, 0.5, g, -event.t as f32, 1.0);
        let mut data = common::data();
        data.width = w;
        data.height = h;
        data.records = vec![record; w * h];
        Ok(Some(data))
    }
    /// A frame of the view's camera size whose records say the view's time (t_emit = −t)
    /// and that it was a view's (g = 3).
    fn view_frame(&self, view: &View, _cancel: &AtomicBool) -> Result<Option<DataFile>, String> {
        let (w, h) = (view.camera.width as usize, view.camera.height as usize);
        let mut data = common::data();
        data.width = w;
        data.height = h;
        data.records = vec![testkit::hit(0, 0.5, 0.5, 3.0, -view.time as f32, 1.0); w * h];
        Ok(Some(data))
    }
    /// No larger than the full frame.
    fn view_refusal(&self, view: &View) -> Option<String> {
        let c = &view.camera;
        (c.width as usize * c.height as usize > FULL.0 * FULL.1).then(|| {
            format!(
                "view.camera: {}×{} is larger than the scene's",
                c.width, c.height
            )
        })
    }
    /// A map whose only content is the event it was made for (in `time_range`).
    fn map(&self, event: ObserverEvent) -> Result<Map, String> {
        let e = MapPoint {
            t: event.t,
            x: event.x,
            y: event.y,
            z: event.z,
            r: 0.0,
        };
        Ok(Map {
            a: Some(1.0),
            event: e,
            horizon_radius: Some(2.0),
            horizon: vec![],
            time_range: [event.t - 1.0, event.t],
            objects: vec![],
            member: None,
        })
    }
    /// A "ray" of two points: the event and (t_emit, 0, 0, 0) of the record.
    fn light_ray(&self, event: ObserverEvent, record: &PixelRecord) -> LightRay {
        let point = |t| MapPoint {
            t,
            x: 0.0,
            y: 0.0,
            z: 0.0,
            r: 0.0,
        };
        LightRay {
            points: vec![point(event.t), point(f64::from(record.t_emit))],
            emission: None,
            travel_time: None,
        }
    }
    fn keyframe(&self, event: ObserverEvent, frame: u32) -> Result<String, String> {
        Ok(format!("frame {frame} at t = {}", event.t))
    }
    /// As `keyframe`, with the view's speed.
    fn view_keyframe(&self, view: &View, frame: u32) -> Result<String, String> {
        Ok(format!(
            "frame {frame} at t = {} moving at {}",
            view.time, view.velocity.speed
        ))
    }
    /// The data file's scene with its observer at `event`.
    fn kernel_input(&self, event: ObserverEvent) -> Result<KernelInput, String> {
        let mut scene = scene::Scene::from_str(&common::scene(), "fake.toml").unwrap();
        scene.observer.event = event.event();
        Ok(KernelInput::new(&scene))
    }
    /// The data file's scene with its observer at the view's event and its velocity.
    fn view_input(&self, view: &View) -> Result<KernelInput, String> {
        let mut scene = scene::Scene::from_str(&common::scene(), "fake.toml").unwrap();
        scene.observer.event = ObserverEvent::of_view(view).event();
        scene.observer.velocity.speed = view.velocity.speed;
        Ok(KernelInput::new(&scene))
    }
    /// Agrees where every sample is a hit on object 0; else names the first other one.
    fn check(
        &self,
        _view: &View,
        samples: &[CheckedSample],
        renderer: &str,
    ) -> Result<Verdict, String> {
        Ok(
            match samples
                .iter()
                .find(|s| s.record.status != RayStatus::Hit || s.record.object != 0)
            {
                None => Verdict::Agree,
                Some(s) => Verdict::Disagree(format!(
                    "{renderer}: sample ({}, {}) {:?}",
                    s.x, s.y, s.record.status
                )),
            },
        )
    }
    /// Moves t by tau, x by speed × tau, keeps the velocity.
    fn fall(
        &self,
        event: ObserverEvent,
        velocity: Velocity,
        tau: f64,
    ) -> Result<(ObserverEvent, Velocity), String> {
        let to = ObserverEvent {
            t: event.t + tau,
            x: event.x + velocity.speed * tau,
            ..event
        };
        Ok((to, velocity))
    }
}

/// Waits (at most ten seconds: a guard against hanging, not a speed check) until `done`.
fn wait_until(what: &str, mut done: impl FnMut() -> bool) {
    for _ in 0..10_000 {
        if done() {
            return;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    panic!("never happened: {what}");
}

/// (generation, level, size, −t_emit, g) of a frame.
type Seen = (u64, Level, (usize, usize), f32, f32);

/// What the newest frame kept is.
fn latest(explorer: &Explorer) -> Option<Seen> {
    explorer.latest().map(|f| {
        let r = f.data.records[0];
        (
            f.generation,
            f.level,
            (f.data.width, f.data.height),
            -r.t_emit,
            r.g,
        )
    })
}

#[test]
fn a_change_of_event_gives_the_coarse_frame_then_the_full_one() {
    let fake = Fake::default();
    fake.held.lock().unwrap().push((3.0, Level::Full));
    let explorer = Explorer::new(fake.clone()).unwrap();
    assert_eq!(explorer.request(event(3.0)), Ok(1));
    // While the full frame is held, the coarse one is what is kept.
    wait_until("the coarse frame", || latest(&explorer).is_some());
    assert_eq!(
        latest(&explorer),
        Some((1, Level::Coarse, COARSE, 3.0, 1.0))
    );
    fake.gate.store(true, Ordering::SeqCst);
    wait_until("the full frame", || {
        latest(&explorer).is_some_and(|f| f.1 == Level::Full)
    });
    assert_eq!(latest(&explorer), Some((1, Level::Full, FULL, 3.0, 2.0)));
    assert_eq!(fake.begun(), [(3.0, Level::Coarse), (3.0, Level::Full)]);
}

#[test]
fn a_newer_request_cancels_the_older_and_is_never_overwritten_by_it() {
    let fake = Fake::default();
    fake.held
        .lock()
        .unwrap()
        .extend([(1.0, Level::Coarse), (2.0, Level::Coarse)]);
    let explorer = Explorer::new(fake.clone()).unwrap();
    assert_eq!(explorer.request(event(1.0)), Ok(1));
    wait_until("the first request's work", || !fake.begun().is_empty());
    // The second request cancels the first: its coarse frame comes back (the fake ignores
    // the flag) but is not kept, and its full frame is never begun.
    assert_eq!(explorer.request(event(2.0)), Ok(2));
    wait_until("the second request's work", || fake.begun().len() == 2);
    assert_eq!(
        latest(&explorer),
        None,
        "the older generation's frame was kept"
    );
    fake.gate.store(true, Ordering::SeqCst);
    wait_until("the newer full frame", || {
        latest(&explorer).is_some_and(|f| f.1 == Level::Full)
    });
    assert_eq!(latest(&explorer), Some((2, Level::Full, FULL, 2.0, 2.0)));
    assert_eq!(
        fake.begun(),
        [
            (1.0, Level::Coarse),
            (2.0, Level::Coarse),
            (2.0, Level::Full)
        ]
    );
}

#[test]
fn an_event_asked_without_refinement_gets_its_coarse_frame_only() {
    let fake = Fake::default();
    let explorer = Explorer::new(fake.clone()).unwrap();
    explorer.request_levels(event(2.0), false).unwrap();
    let first = explorer.first_frame().unwrap();
    assert_eq!((first.generation, first.level), (1, Level::Coarse));
    // A later refined request is traced in full; the unrefined one never was.
    explorer.request(event(3.0)).unwrap();
    for _ in 0..10_000 {
        if explorer.latest().is_some_and(|f| f.level == Level::Full) {
            break;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    assert_eq!(
        fake.begun(),
        vec![
            (2.0, Level::Coarse),
            (3.0, Level::Coarse),
            (3.0, Level::Full)
        ]
    );
}

#[test]
fn the_first_frame_is_the_newest_generations_coarse_frame_or_its_error() {
    let explorer = Explorer::new(Fake::default()).unwrap();
    assert!(explorer.first_frame().is_err(), "no event asked yet");
    explorer.request(event(3.0)).unwrap();
    let first = explorer.first_frame().unwrap();
    assert_eq!((first.generation, first.event.t), (1, 3.0));
    // Coarse unless the full frame was already done.
    assert!(first.level == Level::Coarse || explorer.latest().unwrap().level == Level::Full);
}

#[test]
fn bad_events_are_refused_naming_the_field_and_change_nothing() {
    let explorer = Explorer::new(Fake::default()).unwrap();
    let refused = |e: ObserverEvent| explorer.request(e).unwrap_err();
    let nan = ObserverEvent {
        y: f64::NAN,
        ..event(0.0)
    };
    assert!(refused(nan).starts_with("event.y:"), "{}", refused(nan));
    let far = ObserverEvent {
        z: -200.0,
        ..event(0.0)
    };
    assert!(
        refused(far).starts_with("event.z: -200"),
        "{}",
        refused(far)
    );
    assert!(refused(event(f64::INFINITY)).starts_with("event.t:"));
    assert_eq!(explorer.generation(), 0);
}

#[test]
fn a_view_gets_one_frame_of_its_camera_which_cancels_an_event_and_is_timed() {
    let fake = Fake::default();
    fake.held.lock().unwrap().push((1.0, Level::Coarse));
    let explorer = Explorer::new(fake.clone()).unwrap();
    assert_eq!(explorer.rays_per_ms(), None, "nothing traced yet");
    explorer.request(event(1.0)).unwrap();
    wait_until("the event's work", || !fake.begun().is_empty());
    let mut view: View =
        serde_json::from_value(view_json(6.0, [0.0; 3], 0.3, [1.0, 0.0, 0.0])).unwrap();
    view.camera.width = 3;
    view.camera.height = 2;
    assert_eq!(explorer.request_view(view.clone()), Ok(2));
    wait_until("the view's frame", || latest(&explorer).is_some());
    // One frame of the view's own size, as full; the event's frames are never kept and its
    // full frame never begun.
    assert_eq!(latest(&explorer), Some((2, Level::Full, (3, 2), 6.0, 3.0)));
    let frame = explorer.latest().unwrap();
    assert_eq!(frame.event, ObserverEvent::of_view(&view));
    assert!(frame.trace_ms >= 0.0 && frame.trace_ms.is_finite());
    assert_eq!(fake.begun(), [(1.0, Level::Coarse)]);
    let speed = explorer.rays_per_ms().expect("a frame was traced");
    assert!(speed > 0.0 && speed.is_finite(), "{speed}");
    // A view of more rays than the scene's frame, or beyond the bound, changes nothing.
    let mut big = view.clone();
    big.camera.width = 1000;
    assert!(explorer
        .request_view(big)
        .unwrap_err()
        .starts_with("view.camera:"));
    let mut far = view;
    far.position.y = 1e4;
    let why = explorer.request_view(far).unwrap_err();
    assert!(why.starts_with("view.position.y:"), "{why}");
    assert_eq!(explorer.generation(), 2);
}

async fn send(
    app: &axum::Router,
    request: Request<Body>,
) -> (StatusCode, serde_json::Value, Vec<u8>) {
    let response = app.clone().oneshot(request).await.unwrap();
    let status = response.status();
    let body = response.into_body().collect().await.unwrap().to_bytes();
    let json = serde_json::from_slice(&body).unwrap_or(serde_json::Value::Null);
    (status, json, body.to_vec())
}

/// The explore routes over the stand-in frame source, serving `kernel` when given.
fn stand_in_app(kernel: Option<String>) -> axum::Router {
    app_over(Fake::default(), kernel)
}

/// The explore routes over `fake`, serving `kernel` when given.
fn app_over(fake: Fake, kernel: Option<String>) -> axum::Router {
    let explorer = Explorer::new(fake).unwrap();
    viewer::explore_routes::router(
        common::state(),
        explorer,
        Access::local(common::PORT),
        kernel,
    )
}

/// A view's JSON (`viewer::view::View`) at `time` and `position`, moving at `speed` along
/// `direction`, with a small pinhole camera.
fn view_json(time: f64, position: [f64; 3], speed: f64, direction: [f64; 3]) -> serde_json::Value {
    serde_json::json!({
        "time": time, "position": {"x": position[0], "y": position[1], "z": position[2]},
        "velocity": {"speed": speed, "direction": direction},
        "forward": [1, 0, 0], "up": [0, 0, 1],
        "camera": {"kind": "pinhole", "fov_deg": 60, "width": 8, "height": 4, "samples": 1},
    })
}

/// The refusal's message of a request that must be refused as a bad request.
async fn refusal(app: &axum::Router, request: Request<Body>) -> String {
    let what = format!("{} {}", request.method(), request.uri());
    let (status, answer, body) = send(app, request).await;
    assert_eq!(status, StatusCode::BAD_REQUEST, "{what}");
    let message = answer["error"].as_str();
    message
        .unwrap_or_else(|| panic!("{what}: {}", String::from_utf8_lossy(&body)))
        .to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn asked_after_a_generation_the_frame_route_waits_for_its_frame() {
    let fake = Fake::default();
    // Generation 1's coarse frame waits at the gate until the test opens it.
    fake.held.lock().unwrap().push((7.0, Level::Coarse));
    let app = app_over(fake.clone(), None);
    let body = r#"{"t": 7, "x": 0, "y": 0, "z": 0}"#;
    let (status, answer, _) = send(&app, common::post("/api/explore/event", body)).await;
    assert_eq!(
        (status, answer["generation"].as_u64()),
        (StatusCode::OK, Some(1))
    );
    // Held: the answer comes when the wait is over, without the frame.
    let asked = std::time::Instant::now();
    let (status, answer, _) = send(&app, common::get("/api/explore/frame?after=1")).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert!(
        asked.elapsed() >= viewer::explore_routes::FRAME_WAIT,
        "{answer}"
    );
    assert_eq!(answer["frame"], serde_json::Value::Null, "{answer}");
    // Opened while a request waits: that request answers with the frame.
    let waiting = {
        let app = app.clone();
        tokio::spawn(async move { send(&app, common::get("/api/explore/frame?after=1")).await })
    };
    tokio::time::sleep(Duration::from_millis(20)).await;
    fake.gate.store(true, Ordering::SeqCst);
    let (status, answer, _) = waiting.await.unwrap();
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["frame"]["generation"], 1, "{answer}");
    // A generation newer than the one waited for ends the wait too (at once: it is asked).
    let body = r#"{"t": 8, "x": 0, "y": 0, "z": 0}"#;
    send(&app, common::post("/api/explore/event", body)).await;
    let (_, answer, _) = send(&app, common::get("/api/explore/frame?after=1")).await;
    assert_eq!(answer["generation"], 2, "{answer}");
    for (query, field) in [("after=x", "after"), ("after=1&wait=2", "wait")] {
        let message = refusal(&app, common::get(&format!("/api/explore/frame?{query}"))).await;
        assert!(
            message.starts_with("frame: ") && message.contains(field),
            "{message}"
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_view_frame_route_traces_a_view_and_the_frame_says_how_fast() {
    let app = stand_in_app(None);
    let (_, answer, _) = send(&app, common::get("/api/explore/frame")).await;
    assert_eq!(
        answer["cpu_rays_per_ms"],
        serde_json::Value::Null,
        "{answer}"
    );
    let body = view_json(2.5, [0.1, 0.0, 0.0], 0.5, [0.0, 1.0, 0.0]).to_string();
    let (status, answer, _) = send(&app, common::post("/api/explore/view-frame", &body)).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["generation"], 1);
    let mut answer = serde_json::Value::Null;
    for _ in 0..10_000 {
        answer = send(&app, common::get("/api/explore/frame")).await.1;
        if !answer["frame"].is_null() {
            break;
        }
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    let frame = &answer["frame"];
    assert_eq!(
        (frame["width"].as_u64(), frame["height"].as_u64()),
        (Some(8), Some(4)),
        "{answer}"
    );
    assert_eq!(
        (frame["level"].as_str(), frame["event"]["t"].as_f64()),
        (Some("full"), Some(2.5))
    );
    assert!(
        frame["trace_ms"].as_f64().is_some_and(|ms| ms >= 0.0),
        "{answer}"
    );
    assert!(
        answer["cpu_rays_per_ms"].as_f64().is_some_and(|r| r > 0.0),
        "{answer}"
    );
    // Its channels are served as any frame's: the fake's t_emit is −t.
    let url = "/api/explore/channel/t_emit?generation=1&level=full";
    let (status, _, bytes) = send(&app, common::get(url)).await;
    assert_eq!(status, StatusCode::OK);
    let first = f32::from_le_bytes(bytes[HEADER_LEN..HEADER_LEN + 4].try_into().unwrap());
    assert_eq!(first, -2.5);
    // Asked to wait, the request that asks for a frame answers with it as well (the stand-in
    // traces at once), as the frame route asked after its generation does.
    let body = view_json(3.5, [0.1, 0.0, 0.0], 0.5, [0.0, 1.0, 0.0]).to_string();
    let url = "/api/explore/view-frame?wait=true";
    let (status, asked, _) = send(&app, common::post(url, &body)).await;
    assert_eq!(
        (status, asked["generation"].as_u64()),
        (StatusCode::OK, Some(2))
    );
    let frame = &asked["answer"]["frame"];
    assert_eq!(
        (frame["generation"].as_u64(), frame["event"]["t"].as_f64()),
        (Some(2), Some(3.5)),
        "{asked}"
    );
    assert_eq!(asked["answer"]["generation"], 2, "{asked}");
    for query in ["wait=maybe", "wait=true&after=1"] {
        let url = format!("/api/explore/view-frame?{query}");
        let message = refusal(&app, common::post(&url, &body)).await;
        assert!(message.starts_with("view-frame: "), "{message}");
    }
    let mut big = view_json(0.0, [0.0; 3], 0.0, [1.0, 0.0, 0.0]);
    big["camera"]["width"] = 5000.into();
    let message = refusal(
        &app,
        common::post("/api/explore/view-frame", &big.to_string()),
    )
    .await;
    assert!(message.starts_with("view.camera:"), "{message}");
    let message = refusal(
        &app,
        common::post("/api/explore/view-frame", r#"{"time": 0}"#),
    )
    .await;
    assert!(message.contains("position"), "{message}");
}

#[tokio::test]
async fn godel_view_says_it_is_not_explore_mode() {
    let (status, _, body) = common::send(common::get("/api/explore/info")).await;
    assert_eq!(status, StatusCode::OK);
    let answer: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(answer["explore"], false);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_routes_take_events_and_serve_the_newest_frames_channels() {
    let fake = Fake::default();
    // Generation 2's full frame waits at the gate until the test opens it.
    fake.held.lock().unwrap().push((5.0, Level::Full));
    let app = app_over(fake.clone(), None);
    let (status, info, _) = send(&app, common::get("/api/explore/info")).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(info["explore"], true);
    assert_eq!(info["start"]["t"], 0.0);
    // The viewer's own routes answer behind them.
    let (status, viewer_info, _) = send(&app, common::get("/api/info")).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(viewer_info["width"], common::WIDTH);
    for (body, field) in [
        (r#"{"t": 0, "x": 1e9, "y": 0, "z": 0}"#, "event.x"),
        (r#"{"t": "soon", "x": 0, "y": 0, "z": 0}"#, "event.t"),
        (r#"{"t": 0, "x": 0, "y": 0}"#, "z"),
        (r#"{"t": 0, "x": 0, "y": 0, "z": 0, "w": 1}"#, "w"),
        (
            r#"{"t": 0, "x": 0, "y": 0, "z": 0, "refine": "no"}"#,
            "event.refine",
        ),
    ] {
        let message = refusal(&app, common::post("/api/explore/event", body)).await;
        assert!(message.contains(field), "{field} not in {message}");
    }
    let body = r#"{"t": 4, "x": 0.5, "y": 0, "z": 0}"#;
    let (status, answer, _) = send(&app, common::post("/api/explore/event", body)).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(answer["generation"], 1);
    let mut frame = serde_json::Value::Null;
    for _ in 0..10_000 {
        frame = send(&app, common::get("/api/explore/frame")).await.1["frame"].clone();
        if frame["level"] == "full" {
            break;
        }
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    assert_eq!(frame["generation"], 1);
    assert_eq!(frame["width"], FULL.0);
    assert_eq!(frame["event"]["x"], 0.5);
    let url = "/api/explore/channel/t_emit?generation=1&level=full";
    let (status, _, bytes) = send(&app, common::get(url)).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(
        read_header(&bytes),
        Some((FULL.0, FULL.1, SampleType::F32, 1))
    );
    let first = f32::from_le_bytes(bytes[HEADER_LEN..HEADER_LEN + 4].try_into().unwrap());
    assert_eq!(first, -4.0);
    // Without a name, the record of the frame the server opened on (whose channels
    // /api/gpu serves; there the pixel is a miss), not of a newer one.
    let (status, record, _) = send(&app, common::get("/api/pixel?col=7&row=3")).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(record["status"].as_str(), Some("escaped"), "{record}");
    // The record of the frame the page shows, named; both or neither of generation, level.
    let shown = "/api/pixel?col=7&row=3&generation=1&level=full";
    let (status, record, _) = send(&app, common::get(shown)).await;
    assert_eq!((status, record["g"].as_f64()), (StatusCode::OK, Some(2.0)));
    let coarse_record = "/api/pixel?col=1&row=0&generation=1&level=coarse";
    let (status, record, _) = send(&app, common::get(coarse_record)).await;
    assert_eq!(
        (status, record["g"].as_f64()),
        (StatusCode::OK, Some(1.0)),
        "{record}"
    );
    let half = "/api/pixel?col=7&row=3&generation=1";
    assert_eq!(
        send(&app, common::get(half)).await.0,
        StatusCode::BAD_REQUEST
    );
    // The map's ray of a pixel of that frame (the fake's: from the event to t_emit), for the
    // frame's event; a pixel outside the frame is refused.
    let ray = "/api/explore/ray?generation=1&level=full&col=7&row=3";
    let (status, answer, _) = send(&app, common::get(ray)).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["points"][0]["t"], 4.0);
    assert_eq!(answer["points"][1]["t"], -4.0);
    assert_eq!(
        (answer["status"].as_str(), answer["object"].as_i64()),
        (Some("hit"), Some(0))
    );
    let outside = format!(
        "/api/explore/ray?generation=1&level=full&col={}&row=0",
        FULL.0
    );
    assert_eq!(
        send(&app, common::get(&outside)).await.0,
        StatusCode::BAD_REQUEST
    );
    // The map is made for the event asked; bad events are refused naming the field.
    let (status, map, _) = send(&app, common::get("/api/explore/map?t=4&x=0.5&y=0&z=-1")).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(
        (map["event"]["x"].as_f64(), map["event"]["z"].as_f64()),
        (Some(0.5), Some(-1.0))
    );
    for (query, field) in [
        ("t=4&x=0&y=NaN&z=0", "map.y: NaN is not a finite number"),
        ("t=4&x=0&y=0&z=1e9", "map.z: 1e9 is beyond"),
        ("t=4&x=0&y=0", "z"),
    ] {
        let message = refusal(&app, common::get(&format!("/api/explore/map?{query}"))).await;
        assert!(message.contains(field), "{field} not in {message}");
    }
    let (status, _, text) = send(&app, common::post("/api/explore/keyframe?frame=3", body)).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(String::from_utf8(text).unwrap(), "frame 3 at t = 4");
    let bad = r#"{"t": 4, "x": 0.5, "y": 0}"#;
    assert_eq!(
        send(&app, common::post("/api/explore/keyframe", bad))
            .await
            .0,
        StatusCode::BAD_REQUEST
    );
    // The coarse frame of the newest generation is still served after its full frame (a page
    // may be fetching it): the frame the newest replaced stays, older ones are gone.
    let coarse = "/api/explore/channel/t_emit?generation=1&level=coarse";
    assert_eq!(send(&app, common::get(coarse)).await.0, StatusCode::OK);
    // Several channels in one answer: each the bytes the one-channel route gives, in the
    // order named, the 2-pixel frame's id (one byte a pixel) padded so that t_emit's floats
    // start aligned.
    let mut one_by_one = Vec::new();
    for name in ["id", "t_emit", "u"] {
        let url = format!("/api/explore/channel/{name}?generation=1&level=coarse");
        let (status, _, bytes) = send(&app, common::get(&url)).await;
        assert_eq!(status, StatusCode::OK, "{url}");
        one_by_one.push(bytes);
    }
    let all = "/api/explore/channels?names=id,t_emit,u&generation=1&level=coarse";
    let (status, _, bytes) = send(&app, common::get(all)).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(
        read_header(&one_by_one[0]).map(|h| h.2),
        Some(SampleType::U8)
    );
    assert_eq!(bytes.len(), 20 + one_by_one[1].len() + one_by_one[2].len());
    let parts = split_sequence(&bytes).expect("a sequence of arrays");
    assert_eq!(
        parts,
        one_by_one.iter().map(Vec::as_slice).collect::<Vec<_>>()
    );
    for (query, status, words) in [
        (
            "names=id,pressure",
            StatusCode::NOT_FOUND,
            "no channel 'pressure'",
        ),
        (
            "names=u,id,u",
            StatusCode::BAD_REQUEST,
            "'u' is named twice",
        ),
        ("names=id&colour=red", StatusCode::BAD_REQUEST, "colour"),
        (
            "names=id&generation=x",
            StatusCode::BAD_REQUEST,
            "generation",
        ),
    ] {
        let with_frame = if query.contains("generation") {
            ""
        } else {
            "&generation=1"
        };
        let url = format!("/api/explore/channels?{query}{with_frame}&level=coarse");
        let (got, answer, _) = send(&app, common::get(&url)).await;
        let message = answer["error"].as_str().unwrap_or_default();
        assert_eq!(got, status, "{url}: {message}");
        assert!(message.contains(words), "{url}: {message}");
    }
    let body = r#"{"t": 5, "x": 0.5, "y": 0, "z": 0}"#;
    let (status, answer, _) = send(&app, common::post("/api/explore/event", body)).await;
    assert_eq!(
        (status, answer["generation"].as_u64()),
        (StatusCode::OK, Some(2))
    );
    // Generation 2's coarse frame keeps generation 1's full frame servable (the frame it
    // replaced, which a playing page may still be loading); its full frame ends that.
    for _ in 0..10_000 {
        let frame = send(&app, common::get("/api/explore/frame")).await.1["frame"].clone();
        if frame["generation"] == 2 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    let full_1 = "/api/explore/channel/t_emit?generation=1&level=full";
    assert_eq!(send(&app, common::get(full_1)).await.0, StatusCode::OK);
    assert_eq!(send(&app, common::get(coarse)).await.0, StatusCode::GONE);
    fake.gate.store(true, Ordering::SeqCst);
    for _ in 0..10_000 {
        let frame = send(&app, common::get("/api/explore/frame")).await.1["frame"].clone();
        if frame["generation"] == 2 && frame["level"] == "full" {
            break;
        }
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    let replaced = "/api/explore/channel/t_emit?generation=2&level=coarse";
    assert_eq!(send(&app, common::get(replaced)).await.0, StatusCode::OK);
    for stale in [
        coarse,
        all,
        ray,
        shown,
        "/api/explore/channel/t_emit?generation=1&level=full",
    ] {
        assert_eq!(
            send(&app, common::get(stale)).await.0,
            StatusCode::GONE,
            "{stale}"
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_kernel_input_is_the_scene_seen_from_the_event_asked_for() {
    let app = stand_in_app(None);
    // Before any frame: the scene's own event.
    let (status, input, _) = send(&app, common::get("/api/gpu/input")).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(input["uniforms"]["obs_t"], serde_json::json!([0.0, 0.0]));
    // t = 2.1 is no f32: its hi and lo parts carry it.
    let url = "/api/gpu/input?t=2.1&x=0.25&y=-0.5&z=0.125&draw_buffers=8";
    let (status, input, _) = send(&app, common::get(url)).await;
    assert_eq!(status, StatusCode::OK);
    let t = &input["uniforms"]["obs_t"];
    // JSON carries each f32 in its shortest form: read as f32, as WebGL's uniforms take it.
    let part = |k: usize| f64::from(t[k].as_f64().unwrap() as f32);
    let (hi, lo) = (part(0), part(1));
    assert_eq!(hi, f64::from(2.1f32));
    assert!(lo != 0.0 && (hi + lo - 2.1).abs() < 1e-12, "{hi} + {lo}");
    assert_eq!(
        input["uniforms"]["obs_x"],
        serde_json::json!([0.25, -0.5, 0.125])
    );
    assert_eq!(input["draw_buffers"], 8); // the record and the progress in one draw
                                          // Else the newest frame's event.
    let body = r#"{"t": 4, "x": 0.5, "y": 0, "z": 0}"#;
    let (status, _, _) = send(&app, common::post("/api/explore/event", body)).await;
    assert_eq!(status, StatusCode::OK);
    for _ in 0..10_000 {
        let frame = send(&app, common::get("/api/explore/frame")).await.1["frame"].clone();
        if frame["event"]["t"] == 4.0 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    let (_, input, _) = send(&app, common::get("/api/gpu/input")).await;
    assert_eq!(input["uniforms"]["obs_t"][0], 4.0);
    assert_eq!(input["uniforms"]["obs_x"][0], 0.5);
    for (query, needle) in [
        ("?t=1&x=0", "all of t, x, y and z"),
        ("?t=1&x=1e9&y=0&z=0", "input.x: 1e9 is beyond"),
        ("?t=1&x=0&y=0&z=0&draw_buffers=0", "draw_buffers"),
    ] {
        let message = refusal(&app, common::get(&format!("/api/gpu/input{query}"))).await;
        assert!(message.contains(needle), "{query}: {message}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_view_gets_its_kernel_input_and_a_move_its_free_fall_and_bad_ones_say_why() {
    let app = stand_in_app(None);
    let view = view_json(2.5, [0.25, -0.5, 0.125], 0.5, [1.0, 0.0, 0.0]);
    let (status, input, _) = send(
        &app,
        common::post("/api/explore/input?draw_buffers=8", &view.to_string()),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{input}");
    assert_eq!(input["uniforms"]["obs_t"][0], 2.5);
    assert_eq!(
        input["uniforms"]["obs_x"],
        serde_json::json!([0.25, -0.5, 0.125])
    );
    assert_eq!(input["uniforms"]["velocity"][0], 0.5);
    assert_eq!(input["draw_buffers"], 8); // the record and the progress in one draw
    let step = r#"{"time": 1, "position": {"x": 0, "y": 0, "z": 0},
        "velocity": {"speed": 0.5, "direction": [1, 0, 0]}, "tau": 2}"#;
    let (status, moved, _) = send(&app, common::post("/api/explore/move", step)).await;
    assert_eq!(status, StatusCode::OK, "{moved}");
    assert_eq!(moved["time"], 3.0);
    assert_eq!(moved["position"]["x"], 1.0);
    assert_eq!(moved["velocity"]["speed"], 0.5);
    // The keyframe of a flown view: its own event and velocity (the stand-in writes both).
    let (status, _, text) = send(
        &app,
        common::post("/api/explore/view-keyframe?frame=2", &view.to_string()),
    )
    .await;
    let text = String::from_utf8(text).unwrap();
    assert_eq!(status, StatusCode::OK, "{text}");
    assert_eq!(text, "frame 2 at t = 2.5 moving at 0.5");
    let mut unknown = view.clone();
    unknown["camera"]["zoom"] = 2.into();
    let mut far = view.clone();
    far["position"]["y"] = 1e9.into();
    for (url, body, needle) in [
        (
            "/api/explore/input",
            unknown.to_string(),
            "view.camera.zoom: unknown field `zoom`",
        ),
        (
            "/api/explore/input",
            far.to_string(),
            "view.position.y: 1e9 is beyond",
        ),
        (
            "/api/explore/view-keyframe",
            unknown.to_string(),
            "view.camera.zoom: unknown field `zoom`",
        ),
        (
            "/api/explore/view-keyframe",
            far.to_string(),
            "view.position.y: 1e9 is beyond",
        ),
        (
            "/api/explore/input?draw_buffers=0",
            view.to_string(),
            "draw_buffers",
        ),
        (
            "/api/explore/move",
            step.replace("\"tau\": 2", "\"tau\": 1e9"),
            "move.tau",
        ),
        (
            "/api/explore/move",
            step.replace("\"tau\": 2", "\"tau\": \"x\""),
            "move.tau",
        ),
        (
            "/api/explore/move",
            step.replace("\"time\": 1", "\"time\": 1e300"),
            "move.time: 1e300 is beyond",
        ),
        ("/api/explore/move", step.replace(", \"tau\": 2", ""), "tau"),
    ] {
        let message = refusal(&app, common::post(url, &body)).await;
        assert!(message.contains(needle), "{url} {body}: {message}");
    }
}

/// Issue 36: the refusals named what the request did not write: `event.t` for a view's or a
/// move's `time`, `view.?` for a body cut short; they printed 1e308 with its 309 digits; a
/// channel name that is not UTF-8 got axum's plain-text answer. Each refusal now names the
/// field as the request wrote it, with the route's name, numbers in short form, as JSON.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn refusals_name_what_the_request_wrote_in_short() {
    let app = stand_in_app(None);
    let view = view_json(1e308, [0.0; 3], 0.5, [1.0, 0.0, 0.0]).to_string();
    let step = |time: &str, tau: &str| {
        format!(
            r#"{{"time": {time}, "position": {{"x": 0, "y": 0, "z": 0}},
            "velocity": {{"speed": 0.5, "direction": [1, 0, 0]}}, "tau": {tau}}}"#
        )
    };
    let beyond = "is beyond ±1e2, the scene's bound on coordinates";
    let posts = [
        (
            "view-keyframe",
            view.clone(),
            format!("view.time: 1e308 {beyond}"),
        ),
        ("input", view, format!("view.time: 1e308 {beyond}")),
        (
            "move",
            step("-1e308", "2"),
            format!("move.time: -1e308 {beyond}"),
        ),
        (
            "move",
            step("1", "1e308"),
            "move.tau: 1e308 is not a finite number within ±1000".into(),
        ),
        // The stand-in falls along t: t = 99 + 5 is out of bounds.
        (
            "move",
            step("99", "5"),
            format!("move.tau: after tau = 5, time 104 {beyond}"),
        ),
        (
            "event",
            r#"{"t": 1e308, "x": 0, "y": 0, "z": 0}"#.into(),
            format!("event.t: 1e308 {beyond}"),
        ),
        (
            "view-keyframe",
            r#"{"time": 1, "posi"#.into(),
            "view: EOF while parsing a string at line 1 column 17".into(),
        ),
        (
            "input",
            r#"{"time": 1, "position": {"x": 1"#.into(),
            "view.position: EOF while parsing an object".into(),
        ),
        (
            "move",
            r#"{"time": 1, "velocity": {"spe"#.into(),
            "move.velocity: EOF while parsing a string".into(),
        ),
        (
            "event",
            r#"{"t": 1, "x"#.into(),
            "event: EOF while parsing a string".into(),
        ),
    ];
    for (route, body, want) in posts {
        let url = format!("/api/explore/{route}");
        let message = refusal(&app, common::post(&url, &body)).await;
        assert!(
            message.starts_with(&want),
            "{url}: {message} (wanted {want})"
        );
    }
    let message = refusal(&app, common::get("/api/explore/map?t=0&x=1e308&y=0&z=0")).await;
    assert_eq!(message, format!("map.x: 1e308 {beyond}"));
    // A name that is not UTF-8, in the explore routes and the viewer's own.
    for url in [
        "/api/explore/channel/%FF?generation=1&level=full",
        "/api/gpu/channel/%FF",
        "/api/gpu/image/%FF",
    ] {
        let message = refusal(&app, common::get(url)).await;
        assert!(message.contains("Invalid UTF-8"), "{url}: {message}");
    }
}

/// The page's check (`POST /api/explore/check`, viewer::page_check): the samples sent reach the
/// frame source as records (status and object) with the renderer's name, its verdict comes
/// back; a bad status, a hit without its object, no samples or too many, a body over the cap
/// and an event beyond the bound are refused naming the field; the kernel served is the one
/// given to the router.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_check_hands_its_samples_to_the_source_and_bad_ones_say_why() {
    let app = stand_in_app(Some("void main() {} // served".into()));
    let (status, _, kernel) = send(&app, common::get("/api/gpu/kernel")).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(kernel, b"void main() {} // served");
    let body = |samples: serde_json::Value| {
        serde_json::json!({
            "view": view_json(0.5, [0.0; 3], 0.6, [0.0, 1.0, 0.0]),
            "renderer": "SwiftShader",
            "samples": samples,
        })
        .to_string()
    };
    let hit = serde_json::json!({"x": 1, "y": 2, "status": "hit", "object": 0});
    let (status, answer, _) = send(
        &app,
        common::post("/api/explore/check", &body(serde_json::json!([hit]))),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(
        answer,
        serde_json::json!({"verdict": "agree", "checked": 1, "reason": null})
    );
    let escaped = serde_json::json!({"x": 3, "y": 0, "status": "escaped", "object": -1});
    let (status, answer, _) = send(
        &app,
        common::post(
            "/api/explore/check",
            &body(serde_json::json!([hit, escaped])),
        ),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["verdict"], "disagree");
    assert_eq!(answer["reason"], "SwiftShader: sample (3, 0) Escaped");
    let many = serde_json::Value::Array(vec![hit.clone(); MAX_CHECK_SAMPLES + 1]);
    let far = body(serde_json::json!([hit])).replace("\"time\":0.5", "\"time\":1e9");
    for (request, needle) in [
        (
            body(serde_json::json!([{"x": 1, "y": 2, "status": "lost", "object": 0}])),
            "check.samples[0].status: \"lost\"",
        ),
        (
            body(serde_json::json!([{"x": 1, "y": 2, "status": "hit", "object": -1}])),
            "check.samples[0].object",
        ),
        (body(serde_json::json!([])), "check.samples: 0 samples"),
        (body(many), "check.samples: 129 samples"),
        (far, "check.view.time"),
        (
            body(serde_json::json!([{"x": 1, "y": 2, "status": "hit"}])),
            "object",
        ),
    ] {
        let message = refusal(&app, common::post("/api/explore/check", &request)).await;
        assert!(message.contains(needle), "{request}: {message}");
    }
    let padded =
        body(serde_json::json!([hit])).replace("SwiftShader", &"x".repeat(MAX_CHECK_BYTES));
    let (status, answer, _) = send(&app, common::post("/api/explore/check", &padded)).await;
    assert_eq!(status, StatusCode::PAYLOAD_TOO_LARGE, "{answer}");
}
