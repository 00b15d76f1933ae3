//! The exact tracer's GPU kernel for the page (the `gpu` crate): its source, and what it reads
//! for the scene on show, so that the page traces the frame itself in WebGL2 (page/trace.js)
//! with the very kernel `godel render --gpu` runs.
//!
//! | route | answer |
//! | --- | --- |
//! | `GET /api/gpu/kernel` | the kernel's GLSL ES 3.00 source (text, without `#version 300 es` and the defines the page prepends) |
//! | `GET /api/gpu/input?draw_buffers=N` | what the kernel reads for the data file's embedded scene ([`PageInput`], JSON): uniforms, scene table, the slots of a record, where each light's channel lies, and the defines for N render targets per pass |
//!
//! N is the page's `MAX_DRAW_BUFFERS` (default 4, what every WebGL2 offers); the kernel writes
//! at most [`KERNEL_OUTPUTS`] targets, and never more than a record's slots. A data file whose
//! embedded scene does not trace its own sample grid (another size) gets 404 saying so. In
//! explore mode [`crate::explore_routes`] answers `/api/gpu/input` for an observer's event.

use std::sync::{Arc, OnceLock};

use axum::extract::rejection::QueryRejection;
use axum::extract::{Query, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::{Json, Router};
pub use gpu::KernelInput;
use serde::{Deserialize, Serialize};

use crate::api_error::{no_store, query_value, ApiError};
use crate::state::ViewerState;

/// Render targets the kernel writes at most in one pass (its outputs o0 … o7).
pub const KERNEL_OUTPUTS: usize = 8;
/// Render targets per pass when the page does not say: WebGL2's least MAX_DRAW_BUFFERS.
const DEFAULT_DRAW_BUFFERS: usize = 4;

/// What the page needs to run the kernel on one scene: [`KernelInput`] (its fields at the
/// top level), and the layout the `gpu` crate fixes for it.
#[derive(Clone, Debug, Serialize)]
pub struct PageInput {
    #[serde(flatten)]
    pub input: KernelInput,
    /// Slots of four channels in a record ([`gpu::input::slots`]).
    pub slots: usize,
    /// Light k's channel: [slot, component] ([`gpu::input::light_channel`]).
    pub light_channels: Vec<[usize; 2]>,
    /// Render targets per pass: the page's, at most the slots and [`KERNEL_OUTPUTS`].
    pub draw_buffers: usize,
    /// The source prefix after `#version 300 es` ([`KernelInput::defines`]).
    pub defines: String,
    /// The rounds a tile is traced in (docs/physics.md, "Rounds"; the page runs them as
    /// [`gpu::host`] does): how the draws write the record's and the progress's slots
    /// ([`KernelInput::round_plan`]), the progress's phase of a finished sample, the first
    /// round's budget of passes, and the rounds at most.
    pub plan: gpu::input::RoundPlan,
    pub phase_done: f32,
    pub first_budget: i32,
    pub max_rounds: u32,
}

impl PageInput {
    /// The page's input for `input`, drawn with at most `draw_buffers` targets per pass.
    pub fn new(input: KernelInput, draw_buffers: usize) -> PageInput {
        let slots = input.slots();
        let draw_buffers = input.draw_buffers(draw_buffers.min(KERNEL_OUTPUTS));
        PageInput {
            slots,
            plan: input.round_plan(draw_buffers),
            phase_done: gpu::input::PHASE_DONE,
            first_budget: gpu::host::FIRST_BUDGET,
            max_rounds: gpu::host::MAX_ROUNDS,
            light_channels: (0..input.light_count)
                .map(|k| {
                    let (s, c) = gpu::input::light_channel(k);
                    [s, c]
                })
                .collect(),
            draw_buffers,
            defines: input.defines(draw_buffers),
            input,
        }
    }
}

/// `?draw_buffers=N`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputQuery {
    pub draw_buffers: Option<usize>,
}

/// The render targets per pass a query asks for (at least 1; more than the kernel writes
/// is fine: [`PageInput::new`] takes what it can use).
pub fn draw_buffers(asked: Option<usize>) -> Result<usize, ApiError> {
    match asked {
        None => Ok(DEFAULT_DRAW_BUFFERS),
        Some(0) => Err(ApiError::bad_request(
            "input: draw_buffers must be at least 1",
        )),
        Some(n) => Ok(n),
    }
}

/// The kernel routes' state: the loaded file, and its scene's input once made.
pub struct KernelState {
    viewer: Arc<ViewerState>,
    input: OnceLock<Result<KernelInput, String>>,
}

impl KernelState {
    pub fn new(viewer: Arc<ViewerState>) -> KernelState {
        KernelState {
            viewer,
            input: OnceLock::new(),
        }
    }

    /// The input of the embedded scene, made once; why not, when that scene does not trace
    /// the file's frame.
    fn input(&self) -> Result<&KernelInput, ApiError> {
        let made = self.input.get_or_init(|| input_of(&self.viewer));
        made.as_ref()
            .map_err(|why| ApiError::new(StatusCode::NOT_FOUND, why.clone()))
    }
}

/// The kernel's input for the scene embedded in `viewer`'s data file, or why the page cannot
/// trace that file's frame with it.
fn input_of(viewer: &ViewerState) -> Result<KernelInput, String> {
    let cannot = |why: String| format!("the page cannot trace this data file's frame: {why}");
    let scene = viewer.embedded_scene().map_err(|e| cannot(e.to_string()))?;
    if let Some(why) = gpu::input::refusal(&scene) {
        return Err(cannot(why));
    }
    let input = KernelInput::new(&scene);
    let [w, h] = input.uniforms.size;
    let (fw, fh) = (viewer.data.width, viewer.data.height);
    if (i64::from(w), i64::from(h)) != (fw as i64, fh as i64) {
        return Err(cannot(format!(
            "its embedded scene traces {w}×{h} samples, the file holds {fw}×{fh}"
        )));
    }
    Ok(input)
}

/// The routes, with their own state; merged into [`crate::router`].
pub fn router(state: Arc<KernelState>) -> Router {
    Router::new()
        .route("/api/gpu/kernel", get(kernel))
        .route("/api/gpu/input", get(input))
        .with_state(state)
}

async fn kernel() -> Response {
    kernel_source(gpu::KERNEL)
}

/// The answer of `GET /api/gpu/kernel`: `source` as text, never cached.
pub fn kernel_source(source: &str) -> Response {
    let headers = [
        (header::CONTENT_TYPE, "text/plain; charset=utf-8"),
        (header::CACHE_CONTROL, "no-store"),
    ];
    (headers, source.to_string()).into_response()
}

async fn input(
    State(state): State<Arc<KernelState>>,
    query: Result<Query<InputQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let q = query_value("input", query)?;
    let buffers = draw_buffers(q.draw_buffers)?;
    let page = PageInput::new(state.input()?.clone(), buffers);
    Ok((no_store(), Json(page)).into_response())
}
