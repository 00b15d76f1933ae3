//! The page's JSON contract (crates/viewer/page/contract.d.ts, read by `contract_types`) is
//! the server's: every route the page calls answers real requests with JSON of the type the
//! contract gives it (every field declared, none missing, each of its type), every body built
//! to a type of the contract is accepted, and every field the contract declares is seen in
//! some answer or accepted body. A field renamed, added or dropped on either side fails here.
//! The routes run over the data files of the other tests (a stereo pair's too), a stand-in
//! explore source (the real map and light rays of the test scene) and a stand-in keeper.

use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::{Duration, Instant};

use axum::body::Body;
use axum::http::{Request, StatusCode};
use axum::Router;
use datafile::{DataFile, PixelRecord};
use http_body_util::BodyExt;
use render::map::{LightRay, Map};
use serde_json::{json, Value};
use tower::ServiceExt;
use viewer::explore::{Explorer, FrameSource, Level, ObserverEvent};
use viewer::keep::{ExactJob, Keeper, Recording, Rendered};
use viewer::kernel_routes::KernelInput;
use viewer::page_check::{CheckedSample, Verdict};
use viewer::view::{Velocity, View};
use viewer::{Access, ViewerOptions, ViewerState, WorkLimit};

use crate::common::{self, get, post};
use crate::contract_types::{page_contract, Contract};
use crate::gpu_common;

/// A router and the contract its answers and bodies are held to.
struct Api<'a> {
    app: Router,
    contract: &'a Contract,
}

impl Api<'_> {
    /// The answer to `request`: its status and its JSON (`Null` when it is not JSON).
    async fn send(&self, request: Request<Body>) -> (StatusCode, Value) {
        let response = self.app.clone().oneshot(request).await.unwrap();
        let status = response.status();
        let body = response.into_body().collect().await.unwrap().to_bytes();
        (status, serde_json::from_slice(&body).unwrap_or(Value::Null))
    }

    /// GET `path`, which must answer 200 with JSON of the contract's type `answer`.
    async fn read(&self, path: &str, answer: &str) -> Value {
        let (status, value) = self.send(get(path)).await;
        assert_eq!(status, StatusCode::OK, "GET {path}: {value}");
        (self.contract.check(answer, &value)).unwrap_or_else(|e| panic!("GET {path}: {e}"));
        value
    }

    /// POSTs `body`, which must be of the contract's type `sent`, to `path`, which must accept
    /// it (2xx) and answer with JSON of type `answer` (`None`: a picture or a download).
    async fn write(&self, path: &str, sent: &str, body: &Value, answer: Option<&str>) -> Value {
        (self.contract.check(sent, body))
            .unwrap_or_else(|e| panic!("the body for POST {path}: {e}"));
        let (status, value) = self.send(post(path, &body.to_string())).await;
        assert!(status.is_success(), "POST {path}: {status} {value}");
        if let Some(answer) = answer {
            (self.contract.check(answer, &value)).unwrap_or_else(|e| panic!("POST {path}: {e}"));
        }
        value
    }
}

/// The viewer's routes over `data`, stored as `file`, its images from `file`'s folder.
fn viewer_of<'a>(c: &'a Contract, data: DataFile, file: &Path) -> Api<'a> {
    let options = ViewerOptions {
        texture_folders: Vec::new(),
        work: WorkLimit::new(2, 8),
    };
    let state = ViewerState::new_with(file, data, options).unwrap();
    Api {
        app: viewer::router(Arc::new(state), Access::local(common::PORT)),
        contract: c,
    }
}

/// The test scene of `common` (a ball ahead in Gödel's universe), read.
fn test_scene() -> scene::Scene {
    scene::Scene::from_str(&common::scene(), "contract.toml").unwrap()
}

/// The test scene in the Gödel-type member m² = Ω² = 1 (whose map names the member).
fn member_scene() -> scene::Scene {
    let text = common::scene().replace(
        testkit::GODEL,
        "[spacetime]\nmetric = \"godel-type\"\nm2 = 1.0\nomega = 1.0\n",
    );
    scene::Scene::from_str(&text, "contract.toml").unwrap()
}

/// Explore's frames: `common::data()` for every event and level; the map and light rays are
/// the real ones of `scene` (`render::map`), so that the map has an object with its track.
struct Source {
    scene: fn() -> scene::Scene,
}

impl FrameSource for Source {
    fn start(&self) -> ObserverEvent {
        ObserverEvent::from((self.scene)().observer.event)
    }
    fn bound(&self) -> f64 {
        100.0
    }
    fn frame(
        &self,
        _event: ObserverEvent,
        _level: Level,
        _cancel: &AtomicBool,
    ) -> Result<Option<DataFile>, String> {
        Ok(Some(common::data()))
    }
    fn view_frame(&self, _view: &View, _cancel: &AtomicBool) -> Result<Option<DataFile>, String> {
        Ok(Some(common::data()))
    }
    fn view_refusal(&self, _view: &View) -> Option<String> {
        None
    }
    fn map(&self, event: ObserverEvent) -> Result<Map, String> {
        render::map::map(&(self.scene)(), event.event()).map_err(|(why, _)| why)
    }
    fn light_ray(&self, event: ObserverEvent, record: &PixelRecord) -> LightRay {
        render::map::light_ray(&(self.scene)(), event.event(), record)
    }
    fn keyframe(&self, _event: ObserverEvent, frame: u32) -> Result<String, String> {
        Ok(format!("keyframe {frame}"))
    }
    fn view_keyframe(&self, _view: &View, frame: u32) -> Result<String, String> {
        Ok(format!("keyframe {frame}"))
    }
    fn kernel_input(&self, event: ObserverEvent) -> Result<KernelInput, String> {
        let mut scene = (self.scene)();
        scene.observer.event = event.event();
        Ok(KernelInput::new(&scene))
    }
    fn view_input(&self, view: &View) -> Result<KernelInput, String> {
        self.kernel_input(ObserverEvent::of_view(view))
    }
    fn check(&self, _: &View, _: &[CheckedSample], _: &str) -> Result<Verdict, String> {
        Ok(Verdict::Agree)
    }
    fn fall(
        &self,
        event: ObserverEvent,
        velocity: Velocity,
        tau: f64,
    ) -> Result<(ObserverEvent, Velocity), String> {
        Ok((
            ObserverEvent {
                t: event.t + tau,
                ..event
            },
            velocity,
        ))
    }
}

/// *Render exactly* and *Record*: renders at once, scripts anything.
struct Keep;

impl Keeper for Keep {
    fn name(&self) -> String {
        "contract".into()
    }
    /// A panorama (its two fields of view): the views sent are pinholes (theirs).
    fn own_view(&self) -> View {
        common::view_at_origin("panorama", [None, Some(220.0), Some(25.0)])
    }
    fn check(&self, _view: &View) -> Result<(), String> {
        Ok(())
    }
    fn render(&self, _view: &View, _job: &ExactJob) -> Result<Option<Rendered>, String> {
        Ok(Some(Rendered {
            name: "contract".into(),
            png: b"png".to_vec(),
            exr: b"exr".to_vec(),
            summary: "rendered".into(),
        }))
    }
    fn script(&self, recording: &Recording, _frames: &[u32]) -> Result<String, String> {
        Ok(format!("{} keyframes", recording.keyframes.len()))
    }
}

/// A view as the flying page sends it: a small pinhole camera.
fn view() -> Value {
    json!({
        "time": 0.0, "position": {"x": 0.0, "y": 0.0, "z": 0.0},
        "velocity": {"speed": 0.3, "direction": [1.0, 0.0, 0.0]},
        "forward": [1.0, 0.0, 0.0], "up": [0.0, 0.0, 1.0],
        "camera": {"kind": "pinhole", "fov_deg": 60.0, "width": 8, "height": 4, "samples": 1},
    })
}

/// The routes of `godel view` over the data files of the other tests.
async fn viewing(c: &Contract) {
    let panorama = viewer_of(c, common::data(), Path::new("api-test.exr"));
    let info = panorama.read("/api/info", "Info").await;
    panorama.read("/api/view", "ViewInfo").await;
    // A hit, and a miss (its numbers null).
    panorama.read("/api/pixel?col=0&row=0", "PixelRecord").await;
    panorama.read("/api/pixel?col=7&row=0", "PixelRecord").await;
    panorama.read("/api/gpu/textures", "SceneTextures").await;
    panorama.read("/api/gpu/blackbody", "Blackbody").await;
    panorama
        .read("/api/gpu/input?draw_buffers=4", "KernelInput")
        .await;
    panorama.read("/api/explore/info", "ExploreInfo").await;
    let (status, refusal) = panorama.send(get("/api/pixel?col=99&row=0")).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    c.check("ApiError", &refusal).unwrap();

    // The settings sent back as the page edits them: every kind of texture, a lamp, an axis.
    let mut settings = info["defaults"].clone();
    let ball = &mut settings["objects"]["ball"];
    ball["texture"] = json!({"kind": "checker", "rows": 4, "cols": 8});
    ball["window_texture"] = json!({"kind": "gradient"});
    ball["polarization"] = json!([0.0, 0.0, 1.0]);
    ball["lamps"] = json!([{"u": 0.5, "v": 0.5, "radius_deg": 10.0, "period": 2.0, "phase": 0.0,
        "duty": 0.5, "color": [1.0, 0.5, 0.2]}]);
    settings["grid"] = json!(true);
    panorama
        .write("/api/overlay", "ShadeSettings", &settings, None)
        .await;
    panorama
        .write("/api/keyframe?frame=3", "ShadeSettings", &settings, None)
        .await;
    let ball = &mut settings["objects"]["ball"];
    ball["texture"] = json!({"kind": "earth"});
    ball["window_texture"] = json!({"kind": "uniform", "color": [0.1, 0.2, 0.3]});
    panorama
        .write("/api/png", "ShadeSettings", &settings, None)
        .await;
    // An image file in the data file's folder.
    let folder = tempfile::tempdir().unwrap();
    common::write_png(&folder.path().join("map.png"), 90);
    let beside = viewer_of(c, common::data(), &folder.path().join("view.exr"));
    settings["objects"]["ball"]["texture"] = json!({"kind": "image", "path": "map.png"});
    beside
        .write("/api/png", "ShadeSettings", &settings, None)
        .await;

    // One eye of a stereo pair, the other eye's file beside it.
    let pair = tempfile::tempdir().unwrap();
    let eye = Api {
        app: viewer::router(
            Arc::new(ViewerState::load(&crate::stereo::pair(pair.path())).unwrap()),
            Access::local(common::PORT),
        ),
        contract: c,
    };
    let stereo = eye.read("/api/info", "Info").await;
    assert_eq!(stereo["stereo"]["partner"], true);
    eye.write(
        "/api/stereo/png?layout=anaglyph",
        "ShadeSettings",
        &stereo["defaults"],
        None,
    )
    .await;

    // A full sphere with a light, a uniform texture and an image; then a checker and a
    // gradient; then a pinhole camera.
    let sphere = viewer_of(c, gpu_common::data(), Path::new("gpu-test.exr"));
    let info = sphere.read("/api/info", "Info").await;
    let looked = sphere.read("/api/view", "ViewInfo").await;
    assert_eq!(looked["sphere"], true);
    sphere.read("/api/pixel?col=11&row=3", "PixelRecord").await;
    sphere.read("/api/gpu/textures", "SceneTextures").await;
    let mut patterned = gpu_common::data();
    patterned.header.scene_text = gpu_common::scene_text()
        .replace(
            "{ kind = \"uniform\", color = [0.2, 0.4, 0.6] }",
            "{ kind = \"checker\", rows = 4, cols = 8 }",
        )
        .replace(
            "{ kind = \"image\", builtin = \"earth\" }",
            "{ kind = \"gradient\" }",
        );
    let patterned = viewer_of(c, patterned, Path::new("gpu-test.exr"));
    let textures = patterned.read("/api/gpu/textures", "SceneTextures").await;
    assert_eq!(textures["objects"][0]["kind"], "checker");
    let flat = viewer_of(c, gpu_common::flat(), Path::new("gpu-test.exr"));
    flat.read("/api/view", "ViewInfo").await;

    // Looking around with every camera.
    for camera in [
        json!({"kind": "pinhole", "fov_deg": 100.0, "width": 12, "height": 7}),
        json!({"kind": "panorama", "h_fov_deg": 220.0, "v_fov_deg": 90.0, "width": 12, "height": 7}),
        json!({"kind": "sphere", "width": 12, "height": 6}),
        json!({"kind": "fisheye", "fov_deg": 180.0, "width": 8, "height": 8}),
    ] {
        let body = json!({
            "settings": info["defaults"],
            "view": {"camera": camera, "forward": [1.0, 0.0, 0.0], "up": [0.0, 0.0, 1.0],
                "velocity": {"speed": 0.5, "direction": [0.0, 1.0, 0.0]}, "samples": 4},
        });
        sphere
            .write("/api/look/image", "LookRequest", &body, None)
            .await;
    }
}

/// The routes of `godel explore`, flying included.
async fn exploring(c: &Contract) {
    let explorer = Explorer::new(Source { scene: test_scene }).unwrap();
    let app = Api {
        app: viewer::explore_routes::router(
            common::state(),
            explorer,
            Access::local(common::PORT),
            None,
        ),
        contract: c,
    };
    let start = app.read("/api/explore/info", "ExploreInfo").await["start"].clone();
    let event = json!({"t": 0.5, "x": 0.1, "y": 0.0, "z": 0.0, "refine": false});
    app.write(
        "/api/explore/event",
        "EventRequest",
        &event,
        Some("EventAnswer"),
    )
    .await;
    // The newest frame (a deadline against hanging, not a speed check).
    let until = Instant::now() + Duration::from_secs(60);
    let frame = loop {
        let answer = app.read("/api/explore/frame", "FrameAnswer").await;
        if !answer["frame"].is_null() {
            break answer["frame"].clone();
        }
        assert!(Instant::now() < until, "no frame came");
        tokio::time::sleep(Duration::from_millis(10)).await;
    };
    // A flying page's view traced on the server, answered as an event is.
    app.write(
        "/api/explore/view-frame",
        "View",
        &view(),
        Some("EventAnswer"),
    )
    .await;
    let query = |e: &Value| format!("t={}&x={}&y={}&z={}", e["t"], e["x"], e["y"], e["z"]);
    let map = app
        .read(&format!("/api/explore/map?{}", query(&start)), "ExploreMap")
        .await;
    assert!(map["objects"][0]["at"].is_object(), "{map}");
    assert!(
        map.get("member").is_none(),
        "Gödel's map has no member: {map}"
    );
    // A Gödel-type member's map names the member (`member`, the optional field).
    let member = Api {
        app: viewer::explore_routes::router(
            common::state(),
            Explorer::new(Source {
                scene: member_scene,
            })
            .unwrap(),
            Access::local(common::PORT),
            None,
        ),
        contract: c,
    };
    let in_member = member
        .read(&format!("/api/explore/map?{}", query(&start)), "ExploreMap")
        .await;
    assert_eq!(in_member["member"]["m2"], 1.0, "{in_member}");
    // Its kernel input names the member too (`member`, null in Gödel's universe).
    let input = member
        .read(
            &format!("/api/gpu/input?{}&draw_buffers=4", query(&start)),
            "KernelInput",
        )
        .await;
    assert_eq!(input["member"]["m2"], 1.0, "{input}");
    let (generation, level) = (&frame["generation"], frame["level"].as_str().unwrap());
    for col in [0, 7] {
        let path =
            format!("/api/explore/ray?generation={generation}&level={level}&col={col}&row=1");
        app.read(&path, "LightRay").await;
    }
    let path = format!("/api/gpu/input?{}&draw_buffers=4", query(&start));
    app.read(&path, "KernelInput").await;
    app.write(
        "/api/explore/input?draw_buffers=4",
        "View",
        &view(),
        Some("KernelInput"),
    )
    .await;
    let step = json!({"time": 0.0, "position": {"x": 0.0, "y": 0.0, "z": 0.0},
        "velocity": {"speed": 0.3, "direction": [1.0, 0.0, 0.0]}, "tau": 0.01});
    app.write(
        "/api/explore/move",
        "MoveRequest",
        &step,
        Some("MoveAnswer"),
    )
    .await;
    let check = json!({"view": view(), "renderer": "a GPU",
        "samples": [{"x": 0, "y": 0, "status": "hit", "object": 0},
                    {"x": 7, "y": 0, "status": "escaped", "object": -1}]});
    app.write(
        "/api/explore/check",
        "CheckRequest",
        &check,
        Some("CheckAnswer"),
    )
    .await;
    app.write("/api/explore/view-keyframe?frame=0", "View", &view(), None)
        .await;
    app.write(
        "/api/explore/keyframe?frame=0",
        "ObserverEvent",
        &start,
        None,
    )
    .await;
    // Asked to wait, with what the frame route answers after that generation.
    app.write(
        "/api/explore/view-frame?wait=true",
        "View",
        &view(),
        Some("ViewFrameAnswer"),
    )
    .await;
}

/// *Render exactly* and *Record*.
async fn keeping(c: &Contract) {
    let app = Api {
        app: viewer::keep_routes::router(Keep, WorkLimit::new(1, 1), Access::local(common::PORT)),
        contract: c,
    };
    app.read("/api/explore/view", "OwnView").await;
    app.read("/api/explore/exact", "ExactStatus").await;
    app.write("/api/explore/exact", "View", &view(), Some("ExactStarted"))
        .await;
    let until = Instant::now() + Duration::from_secs(60);
    loop {
        let status = app.read("/api/explore/exact", "ExactStatus").await;
        if status["job"]["state"] == "done" {
            break;
        }
        assert!(Instant::now() < until, "the render did not end: {status}");
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let (status, cancelled) = app.send(post("/api/explore/exact/cancel", "{}")).await;
    assert_eq!(status, StatusCode::OK);
    c.check("ExactCancelled", &cancelled).unwrap();
    let recording = json!({"keyframes": [{"seconds": 0.0, "view": view()},
        {"seconds": 0.5, "view": view()}]});
    app.write("/api/explore/record", "RecordRequest", &recording, None)
        .await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_route_the_page_calls_answers_and_takes_the_contracts_types() {
    let c = page_contract();
    viewing(&c).await;
    exploring(&c).await;
    keeping(&c).await;
    let unseen = c.unseen();
    assert!(
        unseen.is_empty(),
        "declared in contract.d.ts, never seen: {unseen:?}"
    );
}

#[test]
fn every_type_the_contract_names_is_declared() {
    let c = page_contract();
    assert!(c.decls.contains_key("Info"));
    assert_eq!(c.undeclared(), Default::default());
}

/// The checker itself: what it must refuse, it refuses.
#[test]
fn a_missing_an_undeclared_or_a_mistyped_field_is_refused() {
    let c = Contract::parse(
        "// a comment\nexport type Kind = 'a' | 'b';\n\
         export interface Thing {\n  kind: Kind;\n  size?: number;\n  tags: (string | null)[];\n\
         pair: [number, boolean];\n  more: Record<string, Thing>;\n}",
    )
    .unwrap();
    let good = json!({"kind": "a", "tags": ["x", null], "pair": [1, true],
        "more": {"k": {"kind": "b", "size": 2, "tags": [], "pair": [0, false], "more": {}}}});
    c.check("Thing", &good).unwrap();
    assert_eq!(c.unseen(), Vec::<String>::new());
    for (edit, needle) in [
        (json!({"kind": "c"}), "Thing.kind"),
        (json!({"size": "2"}), "Thing.size"),
        (json!({"tags": [1]}), "Thing.tags[0]"),
        (json!({"pair": [1]}), "Thing.pair"),
        (json!({"more": {"k": 1}}), "Thing.more.k"),
        (json!({"colour": "red"}), "declares no field colour"),
    ] {
        let mut bad = good.clone();
        for (k, v) in edit.as_object().unwrap() {
            bad[k] = v.clone();
        }
        let why = c.check("Thing", &bad).unwrap_err();
        assert!(why.contains(needle), "{edit}: {why}");
    }
    let mut missing = good.clone();
    missing.as_object_mut().unwrap().remove("tags");
    assert!(c
        .check("Thing", &missing)
        .unwrap_err()
        .contains("no field tags"));
    assert!(Contract::parse("export interface A { b: number }").is_err());
    let fresh = Contract::parse("export interface A { b?: number; }").unwrap();
    fresh.check("A", &json!({})).unwrap();
    assert_eq!(fresh.unseen(), ["A.b"]);
}
