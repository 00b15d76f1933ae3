//! The routes of explore mode (`godel explore`, [`crate::explore`]), added to the viewer's own:
//!
//! | route | answer |
//! | --- | --- |
//! | `GET /api/explore/info` | `"explore": true`, the scene's observer event, the bound on coordinates, the newest generation (JSON) |
//! | `POST /api/explore/event` (`{"t", "x", "y", "z"[, "refine": false]}`) | starts a new generation for that event (coarse frame, then the full one unless `refine` is false): `{"generation": N}`; 400 naming the field for a bad event |
//! | `POST /api/explore/view-frame[?wait=true]` ([`View`]) | starts a new generation for one frame of that view, at its camera's size and samples (a flying page that finds this CPU faster than its GPU): `{"generation": N}`, the frame kept as `full`; with `wait`, also `"answer"`: what `GET /api/explore/frame?after=N` answers (one request asks for the frame and waits for it); 400 naming the field for a bad view or one of more rays than a frame of the scene's camera |
//! | `GET /api/explore/frame[?after=G]` | the newest frame kept: `{"generation", "level", "event", "width", "height", "supersample", "trace_ms"}` (`frame` null before any), the newest generation, the error of the newest generation, if any, and `cpu_rays_per_ms`, the rays a millisecond of the last frame traced (null before any) (JSON); with `after`, answered once a frame of generation G or newer is kept, a newer generation is asked for or G failed, or after [`FRAME_WAIT`] |
//! | `GET /api/explore/channel/{name}?generation=G&level=L` | a channel of that frame ([`crate::gpu`], [`crate::wire`] array); 410 once it is neither the newest frame nor the one that frame replaced |
//! | `GET /api/explore/channels?names=N,…&generation=G&level=L` | those channels of that frame in one answer, in the order named (a [`crate::wire::sequence`]); 404 naming an unknown channel, 400 for a channel named twice; 410 as for one channel |
//! | `GET /api/explore/map?t=T&x=X&y=Y&z=Z` | the map for an observer at that event ([`render::map::Map`] as JSON: horizon, balls at its time, tracks); 400 naming the field for a bad event |
//! | `GET /api/explore/ray?generation=G&level=L&col=C&row=R` | the light ray of that pixel of that frame, from the observer to its emission event ([`render::map::LightRay`]); 410 as for channels, 400 outside the picture |
//! | `POST /api/explore/keyframe?frame=N` (`{"t", "x", "y", "z"}`) | a sequence-script keyframe (TOML download) that puts the scene's observer at that event |
//! | `POST /api/explore/view-keyframe?frame=N` ([`View`]) | a sequence-script keyframe (TOML download) with the view's observer (event, velocity, axes) and fields of view (a flight's); 400 naming the field |
//! | `GET /api/gpu/input?t=T&x=X&y=Y&z=Z[&draw_buffers=N]` | what the GPU kernel reads to trace the full frame seen from that event (as in [`crate::kernel_routes`]); without an event, from the newest frame's (the scene's own before any) |
//! | `POST /api/explore/input?draw_buffers=N` (a [`View`]: `{"time", "position", "velocity", "forward", "up", "camera"}`) | what the GPU kernel reads to trace that view (the flying page's, page/fly.js); 400 naming the field for a bad view |
//! | `POST /api/explore/move` (`{"time", "position", "velocity", "tau"}`) | where that observer is after `tau` of its proper time falling freely, its velocity there, and the kernel's uniforms of that position (`gpu::input::ObserverUniforms`: its static frame and isometry, which the page does not compute): `{"time", "position", "velocity", "observer": {"obs_static", "obs_to"}}`; 400 naming the field for bad input |
//! | `POST /api/explore/check` | the page's samples traced again by the CPU exact tracer: whether its GPU agrees ([`crate::page_check`]) |
//! | `GET /api/gpu/kernel` | the kernel's source the page traces with: the `gpu` crate's, or the one `godel explore --kernel FILE` serves (as in [`crate::kernel_routes`]) |
//! | [`FRAME_ROUTES`]`?…&generation=G&level=L` | as in [`crate::routes`] and [`crate::look_routes`] (`/api/info`, `/api/pixel`, `/api/png`, `/api/look/png`, `/api/overlay`, …), answered for that frame (the one the page shows; 410 once gone); without a name, for the frame the server opened on (whose channels `/api/gpu/…` serves: what the page shows before it takes a traced frame) |
//!
//! So *Save PNG*, looked pictures, overlays and the file's description always belong to the
//! frame on screen, at its size, never to the first frame the server opened on.
//!
//! The page polls `/api/explore/frame` (waiting for the frame it asked for with `after`, or
//! asking for a view's frame and waiting for it in one request, so that one or a few
//! requests wait for a frame, not one every few milliseconds: each costs the browser's
//! cores on a software renderer), fetches the channels of a frame newer than the one it
//! shows (all it needs in one request, for the same reason), and shades them on the GPU as
//! the viewer's own channels. Like every route these pass [`crate::guard::check`]; channels
//! are encoded within the server's bound on work.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::rejection::{PathRejection, QueryRejection};
use axum::extract::{DefaultBodyLimit, Path, Query, Request, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::{any, get, post};
use axum::{middleware, Json, Router};
use serde::Deserialize;
use spacetime::message::short;
use tower::ServiceExt;

use crate::api_error::{json_body, no_store, path_error, query_value, ApiError};
use crate::explore::{Explorer, Frame, Level, ObserverEvent, EVENT_FIELDS, VIEW_FIELDS};
use crate::gpu::Channel;
use crate::guard::{Access, MAX_BODY_BYTES};
use crate::state::{ViewerOptions, ViewerState};
use crate::view::{Position, Velocity, View};

/// The explore routes' state.
pub struct ExploreState {
    /// The first frame's viewer: texture folders, the bound on work, the page's files.
    pub viewer: Arc<ViewerState>,
    pub explorer: Explorer,
    /// The routes of the last frame asked for, made on first use: (generation, level,
    /// routes over that frame's viewer state, which shares the frame's data).
    prepared: Mutex<Option<(u64, Level, Router)>>,
    /// The kernel source served to the page: the `gpu` crate's unless another is given.
    kernel: Arc<str>,
}

impl ExploreState {
    /// The viewer's routes ([`crate::routes::routes`]) over `frame`, prepared once per frame
    /// with the first frame's texture folders and the server's bound on work.
    fn routes_for(&self, frame: &Frame) -> Result<Router, ApiError> {
        let mut prepared = self.prepared.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((generation, level, routes)) = prepared.as_ref() {
            if (*generation, *level) == (frame.generation, frame.level) {
                return Ok(routes.clone());
            }
        }
        // The older frame's state goes first: no more than one prepared frame in memory.
        *prepared = None;
        let options = ViewerOptions {
            texture_folders: self.viewer.texture_folders().to_vec(),
            work: self.viewer.work().clone(),
        };
        let state = ViewerState::new_with(&self.viewer.path, frame.data.clone(), options)
            .map_err(|e| ApiError::internal(e.to_string()))?;
        let routes = crate::routes::routes(Arc::new(state));
        *prepared = Some((frame.generation, frame.level, routes.clone()));
        Ok(routes)
    }

    /// The frame a request names (`generation` and `level`; 410 once it is gone), or `None`
    /// when it names none: then the first frame's viewer answers, whose channels
    /// `/api/gpu/…` serves and which the page shows until it takes a traced frame.
    fn frame_named(&self, which: FrameQuery) -> Result<Option<Arc<Frame>>, ApiError> {
        match (which.generation, which.level) {
            (Some(generation), Some(level)) => self
                .explorer
                .frame(generation, level)
                .map(Some)
                .ok_or_else(|| gone(generation, level)),
            (None, None) => Ok(None),
            _ => Err(ApiError::bad_request(
                "give both generation and level, or neither",
            )),
        }
    }
}

/// The viewer's routes that explore mode answers for a frame the request names.
pub const FRAME_ROUTES: [&str; 10] = [
    "/api/info",
    "/api/image",
    "/api/png",
    "/api/overlay",
    "/api/keyframe",
    "/api/pixel",
    "/api/view",
    "/api/look/png",
    "/api/look/image",
    "/api/look/overlay",
];

/// The explore routes and [`FRAME_ROUTES`], then (for every other path) the viewer's routes
/// over `viewer` (its first frame), all answering what `access` allows. `kernel`: the GPU
/// kernel's source the page is given instead of the `gpu` crate's (`godel explore --kernel`).
pub fn router(
    viewer: Arc<ViewerState>,
    explorer: Explorer,
    access: Access,
    kernel: Option<String>,
) -> Router {
    let state = Arc::new(ExploreState {
        viewer: viewer.clone(),
        explorer,
        prepared: Mutex::new(None),
        kernel: kernel.map_or_else(|| Arc::from(gpu::KERNEL), Arc::from),
    });
    let mut explore = Router::new()
        .route("/api/explore/info", get(info))
        .route("/api/explore/event", post(event))
        .route("/api/explore/view-frame", post(view_frame))
        .route("/api/explore/frame", get(frame))
        .route("/api/explore/channel/{name}", get(channel))
        .route("/api/explore/channels", get(channels))
        .route("/api/explore/map", get(map))
        .route("/api/explore/ray", get(ray))
        .route("/api/explore/keyframe", post(keyframe))
        .route("/api/explore/view-keyframe", post(view_keyframe))
        .route("/api/gpu/input", get(kernel_input))
        .route("/api/explore/input", post(view_input))
        .route("/api/explore/move", post(fall))
        .route("/api/explore/check", post(check))
        .route("/api/gpu/kernel", get(kernel_text));
    for path in FRAME_ROUTES {
        explore = explore.route(path, any(for_frame));
    }
    let explore = explore
        .with_state(state)
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES))
        .layer(middleware::from_fn_with_state(
            Arc::new(access.clone()),
            crate::guard::check,
        ));
    explore.fallback_service(crate::router(viewer, access))
}

/// `generation=G&level=L`, both or neither, among a request's other query fields.
#[derive(Deserialize)]
struct FrameQuery {
    generation: Option<u64>,
    level: Option<Level>,
}

/// One of [`FRAME_ROUTES`], answered by the viewer's routes over the frame it names.
async fn for_frame(
    State(state): State<Arc<ExploreState>>,
    request: Request,
) -> Result<Response, ApiError> {
    let which = query_value("frame", Query::<FrameQuery>::try_from_uri(request.uri()))?;
    let routes = match state.frame_named(which)? {
        // Preparing reads the scene's textures: work within the server's bound.
        Some(frame) => {
            let explore = state.clone();
            let work = state.viewer.work().admit()?;
            work.run(move || explore.routes_for(&frame)).await??
        }
        None => crate::routes::routes(state.viewer.clone()),
    };
    let response = routes.oneshot(request).await;
    Ok(response.into_response())
}

/// `GET /api/gpu/kernel` in explore mode: the kernel source given, else the `gpu` crate's.
async fn kernel_text(State(state): State<Arc<ExploreState>>) -> Response {
    crate::kernel_routes::kernel_source(&state.kernel)
}

async fn info(State(state): State<Arc<ExploreState>>) -> Response {
    let e = &state.explorer;
    let body = serde_json::json!({
        "explore": true,
        "start": e.start(),
        "bound": e.bound(),
        "generation": e.generation(),
    });
    (no_store(), Json(body)).into_response()
}

/// The body of `POST /api/explore/event`: the event, and whether its full frame is wanted
/// after the coarse one (default yes; a page playing time says no).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EventRequest {
    t: f64,
    x: f64,
    y: f64,
    z: f64,
    #[serde(default = "yes")]
    refine: bool,
}

fn yes() -> bool {
    true
}

async fn event(State(state): State<Arc<ExploreState>>, body: Bytes) -> Result<Response, ApiError> {
    let asked: EventRequest = json_body(&body, "event")?;
    let event = ObserverEvent {
        t: asked.t,
        x: asked.x,
        y: asked.y,
        z: asked.z,
    };
    let generation = state
        .explorer
        .request_levels(event, asked.refine)
        .map_err(ApiError::bad_request)?;
    Ok((
        no_store(),
        Json(serde_json::json!({ "generation": generation })),
    )
        .into_response())
}

/// `POST /api/explore/view-frame`: one frame of the body's view, traced on the server.
/// `?wait=true`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ViewFrameQuery {
    #[serde(default)]
    wait: bool,
}

async fn view_frame(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<ViewFrameQuery>, QueryRejection>,
    body: Bytes,
) -> Result<Response, ApiError> {
    let q = query_value("view-frame", query)?;
    let view = view_body(&state, &body)?;
    // Checking the view reads the scene again: work within the server's bound.
    let work = state.viewer.work().admit()?;
    let explore = state.clone();
    let generation = work
        .run(move || explore.explorer.request_view(view))
        .await?
        .map_err(ApiError::bad_request)?;
    let mut body = serde_json::json!({ "generation": generation });
    if q.wait {
        body["answer"] = frame_answer(&state.explorer, Some(generation)).await;
    }
    Ok((no_store(), Json(body)).into_response())
}

/// The longest `GET /api/explore/frame?after=G` (and `view-frame?wait=true`) waits (well
/// within the server's shutdown grace), and how often it looks meanwhile.
pub const FRAME_WAIT: Duration = Duration::from_millis(250);
const FRAME_LOOK: Duration = Duration::from_millis(2);

/// `?after=G`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WaitQuery {
    after: Option<u64>,
}

/// Whether the page waiting for generation `g` has its answer: a frame of it (or newer)
/// kept, a newer generation asked for, or its error.
fn frame_come(e: &Explorer, g: u64) -> bool {
    e.generation() != g || e.error().is_some() || e.latest().is_some_and(|f| f.generation >= g)
}

async fn frame(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<WaitQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let q = query_value("frame", query)?;
    let body = frame_answer(&state.explorer, q.after).await;
    Ok((no_store(), Json(body)).into_response())
}

/// What `GET /api/explore/frame[?after=G]` answers, after its wait.
async fn frame_answer(e: &Explorer, after: Option<u64>) -> serde_json::Value {
    if let Some(g) = after {
        // At most FRAME_WAIT / FRAME_LOOK looks.
        let deadline = tokio::time::Instant::now() + FRAME_WAIT;
        while !frame_come(e, g) && tokio::time::Instant::now() < deadline {
            tokio::time::sleep(FRAME_LOOK).await;
        }
    }
    let frame = e.latest().map(|f| {
        serde_json::json!({
            "generation": f.generation,
            "level": f.level,
            "event": f.event,
            "width": f.data.picture_size().0,
            "height": f.data.picture_size().1,
            "supersample": f.data.supersample(),
            "trace_ms": f.trace_ms,
        })
    });
    serde_json::json!({
        "frame": frame,
        "generation": e.generation(),
        "error": e.error(),
        "cpu_rays_per_ms": e.rays_per_ms(),
    })
}

/// The answer for a frame that is no longer kept.
fn gone(generation: u64, level: Level) -> ApiError {
    ApiError::new(
        StatusCode::GONE,
        format!("frame {generation} ({level:?}) is no longer the newest; ask /api/explore/frame"),
    )
}

/// `?generation=G&level=coarse|full`.
#[derive(Deserialize)]
struct ChannelQuery {
    generation: u64,
    level: Level,
}

async fn channel(
    State(state): State<Arc<ExploreState>>,
    name: Result<Path<String>, PathRejection>,
    query: Result<Query<ChannelQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let Path(name) = name.map_err(|e| path_error("channel", e))?;
    let q = query_value("channel", query)?;
    let frame = state
        .explorer
        .frame(q.generation, q.level)
        .ok_or_else(|| gone(q.generation, q.level))?;
    let channel = channel_of(&frame, &name)?;
    let bytes = state
        .viewer
        .work()
        .admit()?
        .run(move || channel.encode(&frame.data))
        .await?;
    Ok(crate::gpu_routes::array(bytes))
}

/// The channel `name` of `frame`'s data file; 404 naming it.
fn channel_of(frame: &Frame, name: &str) -> Result<Channel, ApiError> {
    Channel::parse(name, frame.data.lights.len())
        .ok_or_else(|| ApiError::new(StatusCode::NOT_FOUND, format!("no channel '{name}'")))
}

/// `?names=N,…&generation=G&level=coarse|full`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ChannelsQuery {
    names: String,
    generation: u64,
    level: Level,
}

async fn channels(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<ChannelsQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let q = query_value("channels", query)?;
    let frame = state
        .explorer
        .frame(q.generation, q.level)
        .ok_or_else(|| gone(q.generation, q.level))?;
    // Each channel at most once: the answer's size is bounded by the frame's channels.
    let mut wanted: Vec<Channel> = Vec::new();
    for name in q.names.split(',') {
        let channel = channel_of(&frame, name)?;
        if wanted.contains(&channel) {
            return Err(ApiError::bad_request(format!(
                "channels: '{name}' is named twice"
            )));
        }
        wanted.push(channel);
    }
    let bytes = state
        .viewer
        .work()
        .admit()?
        .run(move || crate::wire::sequence(wanted.iter().map(|c| c.encode(&frame.data))))
        .await?;
    Ok(crate::gpu_routes::array(bytes))
}

/// `GET /api/explore/map?t=T&x=X&y=Y&z=Z`.
async fn map(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<ObserverEvent>, QueryRejection>,
) -> Result<Response, ApiError> {
    let event = query_value("map", query)?;
    if let Some(why) = event.refusal_as(state.explorer.bound(), "map", EVENT_FIELDS) {
        return Err(ApiError::bad_request(why));
    }
    let work = state.viewer.work().admit()?;
    let map = work
        .run(move || state.explorer.source().map(event))
        .await?
        .map_err(ApiError::bad_request)?;
    Ok((no_store(), Json(map)).into_response())
}

/// `?generation=G&level=L&col=C&row=R`.
#[derive(Deserialize)]
struct RayQuery {
    generation: u64,
    level: Level,
    col: usize,
    row: usize,
}

/// `GET /api/explore/ray`: the light ray of a pixel of a frame, with the pixel's record.
async fn ray(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<RayQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let q = query_value("ray", query)?;
    let frame = state
        .explorer
        .frame(q.generation, q.level)
        .ok_or_else(|| gone(q.generation, q.level))?;
    let Some(i) = crate::state::picture_sample(&frame.data, q.col, q.row) else {
        let (w, h) = frame.data.picture_size();
        return Err(ApiError::bad_request(format!(
            "pixel ({}, {}) is outside the {w}×{h} image",
            q.col, q.row
        )));
    };
    let work = state.viewer.work().admit()?;
    let body = work
        .run(move || {
            let record = frame.data.records[i];
            let ray = state.explorer.source().light_ray(frame.event, &record);
            serde_json::json!({
                "col": q.col,
                "row": q.row,
                "status": crate::state::status_name(record.status),
                "object": (record.object >= 0).then_some(record.object),
                "points": ray.points,
                "emission": ray.emission,
                "travel_time": ray.travel_time,
            })
        })
        .await?;
    Ok((no_store(), Json(body)).into_response())
}

/// `?frame=N` (default 0).
#[derive(Deserialize)]
struct KeyframeQuery {
    #[serde(default)]
    frame: u32,
}

/// `POST /api/explore/keyframe?frame=N`: the scene's observer at the body's event, as a
/// sequence-script keyframe.
async fn keyframe(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<KeyframeQuery>, QueryRejection>,
    body: Bytes,
) -> Result<Response, ApiError> {
    let q = query_value("keyframe", query)?;
    let event: ObserverEvent = json_body(&body, "event")?;
    if let Some(why) = event.refusal(state.explorer.bound()) {
        return Err(ApiError::bad_request(why));
    }
    let text = state
        .explorer
        .source()
        .keyframe(event, q.frame)
        .map_err(ApiError::bad_request)?;
    Ok(keyframe_download(&state, text))
}

/// `POST /api/explore/view-keyframe?frame=N`: the observer and camera fields of the body's
/// view (a flight's: its event, velocity and axes, fields of view) as a sequence-script
/// keyframe.
async fn view_keyframe(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<KeyframeQuery>, QueryRejection>,
    body: Bytes,
) -> Result<Response, ApiError> {
    let q = query_value("keyframe", query)?;
    let view = view_body(&state, &body)?;
    let work = state.viewer.work().admit()?;
    let source = state.clone();
    let text = work
        .run(move || source.explorer.source().view_keyframe(&view, q.frame))
        .await?
        .map_err(ApiError::bad_request)?;
    Ok(keyframe_download(&state, text))
}

/// A keyframe's text as a TOML download.
fn keyframe_download(state: &ExploreState, text: String) -> Response {
    let name = crate::responses::attachment(&state.viewer, "observer-keyframe.toml");
    crate::responses::toml_download(text, name)
}

/// `?t=T&x=X&y=Y&z=Z&draw_buffers=N`, the event all or nothing.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct InputQuery {
    t: Option<f64>,
    x: Option<f64>,
    y: Option<f64>,
    z: Option<f64>,
    draw_buffers: Option<usize>,
}

/// `GET /api/gpu/input` in explore mode: the kernel's input for the scene seen from the
/// query's event, else from the newest frame's.
async fn kernel_input(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<InputQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let q = query_value("input", query)?;
    let buffers = crate::kernel_routes::draw_buffers(q.draw_buffers)?;
    let event = match (q.t, q.x, q.y, q.z) {
        (Some(t), Some(x), Some(y), Some(z)) => ObserverEvent { t, x, y, z },
        (None, None, None, None) => state
            .explorer
            .latest()
            .map_or_else(|| state.explorer.start(), |f| f.event),
        _ => {
            return Err(ApiError::bad_request(
                "input: give all of t, x, y and z, or none",
            ))
        }
    };
    if let Some(why) = event.refusal_as(state.explorer.bound(), "input", EVENT_FIELDS) {
        return Err(ApiError::bad_request(why));
    }
    let work = state.viewer.work().admit()?;
    let input = work
        .run(move || state.explorer.source().kernel_input(event))
        .await?
        .map_err(ApiError::bad_request)?;
    let page = crate::kernel_routes::PageInput::new(input, buffers);
    Ok((no_store(), Json(page)).into_response())
}

/// `POST /api/explore/input?draw_buffers=N`: the kernel's input for the body's view.
async fn view_input(
    State(state): State<Arc<ExploreState>>,
    query: Result<Query<crate::kernel_routes::InputQuery>, QueryRejection>,
    body: Bytes,
) -> Result<Response, ApiError> {
    let q = query_value("input", query)?;
    let buffers = crate::kernel_routes::draw_buffers(q.draw_buffers)?;
    let view = view_body(&state, &body)?;
    let work = state.viewer.work().admit()?;
    let input = work
        .run(move || state.explorer.source().view_input(&view))
        .await?
        .map_err(ApiError::bad_request)?;
    let page = crate::kernel_routes::PageInput::new(input, buffers);
    Ok((no_store(), Json(page)).into_response())
}

/// The view a request's body sends, its event within the scene's bound; refused naming the
/// field as the view has it (`view.time`, `view.position.x`).
fn view_body(state: &ExploreState, body: &[u8]) -> Result<View, ApiError> {
    let view: View = json_body(body, "view")?;
    let event = ObserverEvent::of_view(&view);
    match event.refusal_as(state.explorer.bound(), "view", VIEW_FIELDS) {
        Some(why) => Err(ApiError::bad_request(why)),
        None => Ok(view),
    }
}

/// The most proper time one `/api/explore/move` spans (either way): a page asks each
/// animation frame for a few hundredths.
const MAX_TAU: f64 = 1e3;

/// The body of `POST /api/explore/move`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MoveRequest {
    time: f64,
    position: Position,
    velocity: Velocity,
    tau: f64,
}

/// `POST /api/explore/move`: the observer after `tau` of its proper time in free fall.
async fn fall(State(state): State<Arc<ExploreState>>, body: Bytes) -> Result<Response, ApiError> {
    let asked: MoveRequest = json_body(&body, "move")?;
    let p = asked.position;
    let at = ObserverEvent {
        t: asked.time,
        x: p.x,
        y: p.y,
        z: p.z,
    };
    let bound = state.explorer.bound();
    if let Some(why) = at.refusal_as(bound, "move", VIEW_FIELDS) {
        return Err(ApiError::bad_request(why));
    }
    if !(asked.tau.is_finite() && asked.tau.abs() <= MAX_TAU) {
        return Err(ApiError::bad_request(format!(
            "move.tau: {} is not a finite number within ±{MAX_TAU}",
            short(asked.tau)
        )));
    }
    let (to, velocity) = state
        .explorer
        .source()
        .fall(at, asked.velocity, asked.tau)
        .map_err(|why| ApiError::bad_request(format!("move.{why}")))?;
    if let Some((i, why)) = to.out_of_bounds(bound) {
        return Err(ApiError::bad_request(format!(
            "move.tau: after tau = {}, {} {why}",
            short(asked.tau),
            VIEW_FIELDS[i]
        )));
    }
    // The kernel's uniforms of the new position, made by the one packer (gpu::input).
    let observer = state
        .explorer
        .source()
        .kernel_input(to)
        .map_err(|why| ApiError::bad_request(format!("move: {why}")))?
        .uniforms
        .observer;
    let body = serde_json::json!({
        "time": to.t,
        "position": { "x": to.x, "y": to.y, "z": to.z },
        "velocity": velocity,
        "observer": observer,
    });
    Ok((no_store(), Json(body)).into_response())
}

/// `POST /api/explore/check`: the page's samples traced again by the CPU ([`crate::page_check`]).
async fn check(State(state): State<Arc<ExploreState>>, body: Bytes) -> Result<Response, ApiError> {
    let asked = crate::page_check::request(&body, state.explorer.bound())?;
    let checked = asked.samples.len();
    let work = state.viewer.work().admit()?;
    let verdict = work
        .run(move || (state.explorer.source()).check(&asked.view, &asked.samples, &asked.renderer))
        .await?
        .map_err(ApiError::bad_request)?;
    Ok(crate::page_check::answer(verdict, checked))
}
