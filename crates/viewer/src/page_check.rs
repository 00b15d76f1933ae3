//! The page's check of its own GPU tracer (explore's flight, page/fly.js): a driver may compile
//! the kernel and run it wrongly (docs/physics.md, "The GPU kernel"), so the page sends a few
//! of the samples it traced and the server traces them again with the CPU exact tracer,
//! holding them together exactly as `godel render --gpu` holds its own trace (`gpu::check`:
//! the same status and object, a few grazing samples allowed). A page told that they disagree
//! stops tracing and shows the server's frames, saying which renderer was refused and why.
//!
//! | route | answer |
//! | --- | --- |
//! | `POST /api/explore/check` (`{"view", "renderer", "samples": [{"x", "y", "status", "object"}]}`) | `{"verdict", "checked", "reason"}`: verdict `agree`, `disagree` (reason: how many differ, and the first) or `unchecked` (reason: why the CPU cannot trace them); 400 naming the field for a bad request, 413 for a body over [`MAX_CHECK_BYTES`] |
//!
//! `view` is the view traced (`viewer.explore.view()`, with the camera's width, height and
//! samples of the frame the samples come from: [`crate::view::View`]); `x`, `y` a cell of its
//! sample grid; `status` a record's status as `/api/pixel` names it, `object` its object (−1
//! for a miss). Bounded: at most [`MAX_CHECK_SAMPLES`] samples and [`MAX_CHECK_BYTES`] of body,
//! traced on the server's work pool within its limits ([`crate::limit`]).

use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use datafile::record::RayStatus;
use datafile::PixelRecord;
use serde::Deserialize;

use crate::api_error::{json_body, no_store, ApiError};
pub use crate::explore::{CheckedSample, Verdict};
use crate::explore::{ObserverEvent, VIEW_FIELDS};
use crate::state::status_name;
use crate::view::View;

/// The most samples one check traces (a few dozen are sent; the CPU traces each again).
pub const MAX_CHECK_SAMPLES: usize = 128;
/// The largest body a check may send (a view and [`MAX_CHECK_SAMPLES`] short records fit).
pub const MAX_CHECK_BYTES: usize = 32 << 10;
/// The longest renderer name kept (WebGL's `RENDERER` string), in characters.
const MAX_RENDERER_CHARS: usize = 200;

/// The body of `POST /api/explore/check`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CheckRequest {
    view: View,
    renderer: String,
    samples: Vec<SampleJson>,
}

/// A sample as the page sends it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SampleJson {
    x: u32,
    y: u32,
    status: String,
    object: i32,
}

/// The sample `k` the page sent, as a record; refused naming the field.
fn sample(k: usize, s: &SampleJson) -> Result<CheckedSample, String> {
    let status = RayStatus::ALL
        .into_iter()
        .find(|&st| status_name(st) == s.status)
        .ok_or_else(|| {
            let names: Vec<&str> = RayStatus::ALL.into_iter().map(status_name).collect();
            format!(
                "check.samples[{k}].status: {:?} is none of {}",
                s.status,
                names.join(", ")
            )
        })?;
    let object = match status {
        RayStatus::Hit if s.object >= 0 => s.object,
        RayStatus::Hit => {
            return Err(format!(
                "check.samples[{k}].object: a hit names its object (0 or more), not {}",
                s.object
            ))
        }
        _ => PixelRecord::NO_OBJECT,
    };
    Ok(CheckedSample {
        x: s.x,
        y: s.y,
        record: PixelRecord {
            object,
            ..PixelRecord::miss(status)
        },
    })
}

/// A request of `POST /api/explore/check`, checked: the view, the renderer's name (cut to
/// [`MAX_RENDERER_CHARS`]) and the samples.
pub struct Checked {
    pub view: View,
    pub renderer: String,
    pub samples: Vec<CheckedSample>,
}

/// The body of `POST /api/explore/check` read and checked (events within `bound`); a refusal
/// names the field, or is 413 for a body over [`MAX_CHECK_BYTES`].
pub fn request(body: &[u8], bound: f64) -> Result<Checked, ApiError> {
    if body.len() > MAX_CHECK_BYTES {
        return Err(ApiError::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!(
                "check: the body is {} bytes, at most {MAX_CHECK_BYTES}",
                body.len()
            ),
        ));
    }
    let asked: CheckRequest = json_body(body, "check")?;
    if asked.samples.is_empty() || asked.samples.len() > MAX_CHECK_SAMPLES {
        return Err(ApiError::bad_request(format!(
            "check.samples: {} samples, give 1 to {MAX_CHECK_SAMPLES}",
            asked.samples.len()
        )));
    }
    let renderer: String = asked.renderer.chars().take(MAX_RENDERER_CHARS).collect();
    let event = ObserverEvent::of_view(&asked.view);
    if let Some(why) = event.refusal_as(bound, "check.view", VIEW_FIELDS) {
        return Err(ApiError::bad_request(why));
    }
    let samples = (asked.samples.iter().enumerate())
        .map(|(k, s)| sample(k, s))
        .collect::<Result<Vec<_>, _>>()
        .map_err(ApiError::bad_request)?;
    Ok(Checked {
        view: asked.view,
        renderer,
        samples,
    })
}

/// The answer of `POST /api/explore/check` for `checked` samples.
pub fn answer(verdict: Verdict, checked: usize) -> Response {
    let (verdict, reason) = match verdict {
        Verdict::Agree => ("agree", None),
        Verdict::Disagree(why) => ("disagree", Some(why)),
        Verdict::Unchecked(why) => ("unchecked", Some(why)),
    };
    let body = serde_json::json!({ "verdict": verdict, "checked": checked, "reason": reason });
    (no_store(), Json(body)).into_response()
}
