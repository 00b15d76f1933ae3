//! The routes of *Render exactly* and *Record* in explore mode ([`crate::keep`]), beside
//! [`crate::explore_routes`]:
//!
//! | route | answer |
//! | --- | --- |
//! | `GET /api/explore/view` | the scene's own view ([`View`]) and the recording's bounds (JSON) |
//! | `POST /api/explore/exact` ([`View`]) | starts the exact render of that view: 202 `{"job": N}`; 400 naming the field (`view.FIELD`) for a bad view or one beyond the memory budget; 429 while another exact render runs |
//! | `GET /api/explore/exact` | the newest exact render: `{"job": {"id", "state", "done", "total", "seconds", "error", "summary", "png", "exr"}}` (`job` null before any; `png`, `exr`: the files' URLs once done) |
//! | `POST /api/explore/exact/cancel` (`{}`) | cancels the render under way (it stops between tiles) |
//! | `GET /api/explore/exact/{N}/{png,exr}` | a file of render N (download); 410 once a newer render has started |
//! | `POST /api/explore/record` ([`Recording`]) | the sequence script of that flight (TOML download); 400 naming the field (`recording.keyframes[i].…`) |
//!
//! Bounds: one exact render at a time, on a thread of its own (the tracer's pool is the
//! keeper's); the files of only the newest one are kept, in memory, and dropped when the next
//! starts (nothing is written to disk); the render is checked against the memory budget
//! before it starts, and cancelled when the server stops (the routes' state is dropped).
//! Bodies pass [`crate::guard::check`] (JSON, at most [`MAX_BODY_BYTES`]); checks run within
//! the server's bound on work ([`crate::WorkLimit`]). A recording's script is made on a slot
//! of its own, one at a time with [`SCRIPTS_WAITING`] more waiting (then 503): its work is
//! bounded ([`Recording::frames`]) but may take seconds for an hour's flight, and no shading
//! or other route of the server waits for it.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use axum::body::Bytes;
use axum::extract::rejection::PathRejection;
use axum::extract::{DefaultBodyLimit, Path, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{middleware, Json, Router};

use crate::api_error::{json_body, no_store, path_error, ApiError};
use crate::guard::{Access, MAX_BODY_BYTES};
use crate::keep::{ExactJob, JobState, Keeper, Recording, MAX_KEYFRAMES, RECORD_FPS};
use crate::limit::WorkLimit;
use crate::view::View;

/// How many recordings may wait while one is made into a script.
pub const SCRIPTS_WAITING: usize = 4;

/// The keep routes' state: the keeper, the newest exact render.
struct KeepState {
    keeper: Arc<dyn Keeper>,
    work: WorkLimit,
    /// The slot recordings are made into scripts on (apart from `work`).
    scripts: WorkLimit,
    newest: Mutex<Option<Arc<ExactJob>>>,
    jobs: AtomicU64,
}

impl KeepState {
    fn newest(&self) -> Option<Arc<ExactJob>> {
        self.newest
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }
}

impl Drop for KeepState {
    /// The server stops: the render under way stops between tiles.
    fn drop(&mut self) {
        if let Some(job) = self.newest() {
            job.cancel.store(true, Ordering::SeqCst);
        }
    }
}

/// The keep routes over `keeper`, within the server's bound on work `work`, answering what
/// `access` allows.
pub fn router(keeper: impl Keeper, work: WorkLimit, access: Access) -> Router {
    let state = Arc::new(KeepState {
        keeper: Arc::new(keeper),
        work,
        scripts: WorkLimit::of("recordings being made into scripts", 1, SCRIPTS_WAITING),
        newest: Mutex::new(None),
        jobs: AtomicU64::new(0),
    });
    Router::new()
        .route("/api/explore/view", get(own_view))
        .route("/api/explore/exact", post(start).get(status))
        .route("/api/explore/exact/cancel", post(cancel))
        .route("/api/explore/exact/{id}/{file}", get(file))
        .route("/api/explore/record", post(record))
        .with_state(state)
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES))
        .layer(middleware::from_fn_with_state(
            Arc::new(access),
            crate::guard::check,
        ))
}

async fn own_view(State(state): State<Arc<KeepState>>) -> Response {
    let body = serde_json::json!({
        "view": state.keeper.own_view(),
        "max_keyframes": MAX_KEYFRAMES,
        "record_fps": RECORD_FPS,
    });
    (no_store(), Json(body)).into_response()
}

/// `POST /api/explore/exact`: checks the view, then renders it on a thread of its own.
async fn start(State(state): State<Arc<KeepState>>, body: Bytes) -> Result<Response, ApiError> {
    let view: View = json_body(&body, "view")?;
    if let Some(why) = view.refusal() {
        return Err(ApiError::bad_request(why));
    }
    let busy = |job: &ExactJob| {
        ApiError::new(
            StatusCode::TOO_MANY_REQUESTS,
            format!(
                "exact render {} is under way: wait for it or cancel it first",
                job.id
            ),
        )
    };
    if let Some(job) = state.newest().filter(|j| j.state() == JobState::Rendering) {
        return Err(busy(&job));
    }
    let (keeper, checked) = (state.keeper.clone(), view.clone());
    state
        .work
        .admit()?
        .run(move || keeper.check(&checked))
        .await?
        .map_err(ApiError::bad_request)?;
    let job = {
        let mut newest = state.newest.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(job) = newest.as_ref().filter(|j| j.state() == JobState::Rendering) {
            return Err(busy(job));
        }
        let id = state.jobs.fetch_add(1, Ordering::SeqCst) + 1;
        // The older render's files go now: one render's files in memory at a time.
        let job = Arc::new(ExactJob::new(id, view));
        *newest = Some(job.clone());
        job
    };
    let (keeper, running) = (state.keeper.clone(), job.clone());
    let spawned = std::thread::Builder::new()
        .name("exact".into())
        .spawn(move || running.run(keeper.as_ref()));
    if let Err(e) = spawned {
        *job.outcome.lock().unwrap_or_else(|e| e.into_inner()) =
            Some(Err(format!("cannot start the render: {e}")));
        job.finished.store(true, Ordering::SeqCst);
    }
    Ok((
        StatusCode::ACCEPTED,
        no_store(),
        Json(serde_json::json!({ "job": job.id })),
    )
        .into_response())
}

/// `GET /api/explore/exact`: the newest render's state.
async fn status(State(state): State<Arc<KeepState>>) -> Response {
    let job = state.newest().map(|job| {
        // Before the outcome's lock, which `state` takes too.
        let job_state = job.state();
        let outcome = job.outcome.lock().unwrap_or_else(|e| e.into_inner());
        let (error, summary, files) = match &*outcome {
            Some(Ok(r)) => (None, Some(r.summary.clone()), true),
            Some(Err(why)) => (Some(why.clone()), None, false),
            None => (None, None, false),
        };
        let url = |kind: &str| files.then(|| format!("/api/explore/exact/{}/{kind}", job.id));
        serde_json::json!({
            "id": job.id,
            "state": job_state,
            "done": job.done.load(Ordering::SeqCst),
            "total": job.total.load(Ordering::SeqCst),
            "seconds": *job.seconds.lock().unwrap_or_else(|e| e.into_inner()),
            "error": error,
            "summary": summary,
            "png": url("png"),
            "exr": url("exr"),
        })
    });
    (no_store(), Json(serde_json::json!({ "job": job }))).into_response()
}

/// `POST /api/explore/exact/cancel`.
async fn cancel(State(state): State<Arc<KeepState>>) -> Response {
    let job = state.newest().filter(|j| j.state() == JobState::Rendering);
    if let Some(job) = &job {
        job.cancel.store(true, Ordering::SeqCst);
    }
    let body = serde_json::json!({ "cancelled": job.map(|j| j.id) });
    (no_store(), Json(body)).into_response()
}

/// `GET /api/explore/exact/{id}/{png|exr}`: a file of the newest render.
async fn file(
    State(state): State<Arc<KeepState>>,
    path: Result<Path<(String, String)>, PathRejection>,
) -> Result<Response, ApiError> {
    let Path((id, kind)) = path.map_err(|e| path_error("exact", e))?;
    let id: u64 = id.parse().map_err(|_| {
        ApiError::bad_request(format!(
            "exact: `{id}` is not the number of a render (/api/explore/exact/N/png or …/exr)"
        ))
    })?;
    let job = state.newest().filter(|j| j.id == id).ok_or_else(|| {
        ApiError::new(
            StatusCode::GONE,
            format!("exact render {id} is not the newest; ask /api/explore/exact"),
        )
    })?;
    let job_state = job.state();
    let outcome = job.outcome.lock().unwrap_or_else(|e| e.into_inner());
    let Some(Ok(rendered)) = &*outcome else {
        return Err(ApiError::new(
            StatusCode::NOT_FOUND,
            format!("exact render {id} has no files (it is {job_state:?})"),
        ));
    };
    let (bytes, content_type) = match kind.as_str() {
        "png" => (rendered.png.clone(), "image/png"),
        "exr" => (rendered.exr.clone(), "image/x-exr"),
        _ => {
            return Err(ApiError::new(
                StatusCode::NOT_FOUND,
                format!("no file '{kind}': png or exr"),
            ))
        }
    };
    let name = crate::responses::attachment_named(&rendered.name, &kind);
    Ok(crate::responses::download(bytes, content_type, name))
}

/// `POST /api/explore/record`: the sequence script of a recorded flight.
async fn record(State(state): State<Arc<KeepState>>, body: Bytes) -> Result<Response, ApiError> {
    let recording: Recording = json_body(&body, "recording")?;
    let frames = recording.frames().map_err(ApiError::bad_request)?;
    let keeper = state.keeper.clone();
    let text = state
        .scripts
        .admit()?
        .run(move || keeper.script(&recording, &frames))
        .await?
        .map_err(ApiError::bad_request)?;
    let name = format!("{}-flight", state.keeper.name());
    Ok(crate::responses::toml_download(
        text,
        crate::responses::attachment_named(&name, "toml"),
    ))
}
