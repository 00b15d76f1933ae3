//! The HTTP interface: the page's files, and a small JSON/binary API over [`ViewerState`].
//!
//! | route | answer |
//! | --- | --- |
//! | `GET /`, `/viewer.js`, `/viewer.css` | the page ([`crate::assets`]) |
//! | `GET /api/info` | file, size, objects, light count, default settings, stereo eye (JSON) |
//! | `POST /api/image` (settings JSON) | the shaded picture as raw RGBA; `X-Image-Width`, `X-Image-Height`, `Server-Timing` |
//! | `POST /api/png` (settings JSON) | the shaded picture as a PNG download |
//! | `POST /api/stereo/png?layout=L` (settings JSON) | of one eye of a stereo pair, both eyes shaded with those settings in layout `L` (`side-by-side`, `over-under`, `anaglyph`; default the pair's; `shade::stereo::compose`) as a PNG; 404 without the other eye |
//! | `POST /api/overlay` (settings JSON) | the overlay layer (orientation marks, legend, labels; `shade::layer`) of the picture as an RGBA PNG, 204 when there is nothing to draw |
//! | `POST /api/keyframe?frame=N` (settings JSON) | a sequence-script keyframe (TOML) download |
//! | `GET /api/pixel?col=C&row=R` | that pixel's record (JSON) |
//! | `GET /api/explore/info` | `{"explore": false}`: not explore mode ([`crate::explore_routes`] answers it there) |
//! | `GET /api/gpu/…`, `GET /api/view`, `POST /api/look/…` | [`crate::gpu_routes`], [`crate::kernel_routes`], [`crate::look_routes`] |
//!
//! Every request first passes [`crate::guard::check`] (Host, Origin, JSON bodies, body size:
//! 403, 415, 413). Bad requests (malformed or unknown settings, pixel outside the image) get
//! 400 with `{"error": "..."}` naming the field; nothing a client sends can panic the server.
//! Shading runs on tokio's blocking threads, and within it on rayon's pool, so slow shading
//! never stalls the hover requests; at most as many pictures as [`crate::limit::WorkLimit`]
//! allows are shaded at once, a few more wait, the rest get 503.

use std::sync::Arc;
use std::time::Instant;

use axum::body::Bytes;
use axum::extract::rejection::QueryRejection;
use axum::extract::{DefaultBodyLimit, Query, State};
use axum::http::{header, HeaderName, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{middleware, Json, Router};
use serde::Deserialize;

pub use crate::api_error::ApiError;
use crate::api_error::{json_body, no_store, query_value};
use crate::encode;
use crate::guard::{Access, MAX_BODY_BYTES};
use crate::responses::{attachment, overlay_png, png_download, rgba_picture, toml_download};
use crate::state::ViewerState;
use scene::{Eye, Layout};
use shade::{ShadeSettings, Shading};

/// The server's routes over one loaded data file, answering requests that `access` allows.
pub fn router(state: Arc<ViewerState>, access: Access) -> Router {
    routes(state)
        // Layers added after the merges cover every route, the GPU and look ones included.
        // The guard reads POST bodies up to its own cap; the extractors' limit must not be lower.
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES))
        .layer(middleware::from_fn_with_state(
            Arc::new(access),
            crate::guard::check,
        ))
}

/// [`router`] without the guard: for explore mode, which answers some routes for the frame on
/// screen through these after its own guard ([`crate::explore_routes`]).
pub fn routes(state: Arc<ViewerState>) -> Router {
    let mut router = Router::new();
    for (path, content_type, body) in crate::assets::FILES {
        router = router.route(
            path,
            get(move || async move { ([(header::CONTENT_TYPE, content_type)], body) }),
        );
    }
    router
        .route("/api/info", get(info))
        .route("/api/image", post(image))
        .route("/api/png", post(png))
        .route("/api/stereo/png", post(stereo_png))
        .route("/api/overlay", post(overlay))
        .route("/api/keyframe", post(keyframe))
        .route("/api/pixel", get(pixel))
        .route("/api/explore/info", get(not_exploring))
        .with_state(state.clone())
        .merge(crate::gpu_routes::router(Arc::new(
            crate::gpu_routes::GpuState::new(state.clone()),
        )))
        .merge(crate::kernel_routes::router(Arc::new(
            crate::kernel_routes::KernelState::new(state.clone()),
        )))
        .merge(crate::look_routes::router(Arc::new(
            crate::look_routes::LookState::new(state),
        )))
}

/// Parses the settings JSON sent by the page and prepares them with the `shade` crate
/// (which checks every value and loads the textures); the message names the field.
pub fn parse_settings(
    state: &ViewerState,
    body: &[u8],
) -> Result<(ShadeSettings, Shading), ApiError> {
    let settings: ShadeSettings = json_body(body, "settings")?;
    let shading = state
        .prepare(&settings)
        .map_err(|e| ApiError::bad_request(format!("settings: {e}")))?;
    Ok((settings, shading))
}

/// Runs `job` on a blocking thread within the state's bound on shading work (503 when too
/// many are waiting); a panic there (a bug, never input) becomes a 500.
async fn blocking<T: Send + 'static>(
    state: &ViewerState,
    job: impl FnOnce() -> T + Send + 'static,
) -> Result<T, ApiError> {
    state.work().admit()?.run(job).await
}

async fn not_exploring() -> impl IntoResponse {
    (no_store(), Json(serde_json::json!({ "explore": false })))
}

async fn info(State(state): State<Arc<ViewerState>>) -> impl IntoResponse {
    (no_store(), Json(state.info()))
}

async fn image(State(state): State<Arc<ViewerState>>, body: Bytes) -> Result<Response, ApiError> {
    let (bytes, width, height, shade_ms, encode_ms) = blocking(&state.clone(), move || {
        // Preparing (checking settings, loading textures) counts as shading.
        let started = Instant::now();
        let (_, shading) = parse_settings(&state, &body)?;
        let mut rgb = Vec::new();
        state.shade_rgb(&shading, &mut rgb);
        let shaded = Instant::now();
        let bytes = encode::rgba_from_rgb(&rgb);
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        Ok::<_, ApiError>((
            bytes,
            state.data.picture_size().0 as u32,
            state.data.picture_size().1 as u32,
            ms(shaded - started),
            ms(shaded.elapsed()),
        ))
    })
    .await??;
    let timing = format!("shade;dur={shade_ms:.2}, encode;dur={encode_ms:.2}");
    let mut response = rgba_picture(bytes, width, height);
    response.headers_mut().insert(
        HeaderName::from_static("server-timing"),
        HeaderValue::from_str(&timing).expect("ASCII"),
    );
    Ok(response)
}

async fn png(State(state): State<Arc<ViewerState>>, body: Bytes) -> Result<Response, ApiError> {
    let disposition = attachment(&state, "png");
    let bytes = blocking(&state.clone(), move || {
        let (_, shading) = parse_settings(&state, &body)?;
        encode::png(&state.shade(&shading))
            .map_err(|e| ApiError::internal(format!("encoding PNG: {e}")))
    })
    .await??;
    Ok(png_download(bytes, disposition))
}

/// `?layout=side-by-side|over-under|anaglyph` (default: the pair's).
#[derive(Deserialize)]
struct StereoQuery {
    layout: Option<LayoutName>,
}

/// A stereo layout as the query names it.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum LayoutName {
    SideBySide,
    OverUnder,
    Anaglyph,
}

impl From<LayoutName> for Layout {
    fn from(name: LayoutName) -> Layout {
        match name {
            LayoutName::SideBySide => Layout::SideBySide,
            LayoutName::OverUnder => Layout::OverUnder,
            LayoutName::Anaglyph => Layout::Anaglyph,
        }
    }
}

/// Both eyes of a stereo pair shaded with one set of settings and put into one picture, as
/// `godel shade NAME.left.exr` does; 404 for a mono file or without the other eye's file.
async fn stereo_png(
    State(state): State<Arc<ViewerState>>,
    query: Result<Query<StereoQuery>, QueryRejection>,
    body: Bytes,
) -> Result<Response, ApiError> {
    let q = query_value("stereo", query)?;
    let not_a_pair = || {
        ApiError::new(
            StatusCode::NOT_FOUND,
            "this data file is not one eye of a stereo pair",
        )
    };
    let stereo = state.stereo().ok_or_else(not_a_pair)?;
    let (eye, layout) = (stereo.eye, q.layout.map_or(stereo.layout, Layout::from));
    let missing = ApiError::new(
        StatusCode::NOT_FOUND,
        format!(
            "the other eye's data file of this stereo pair was not beside the {} eye's",
            eye.name()
        ),
    );
    stereo.partner.as_ref().ok_or_else(|| missing.clone())?;
    let bytes = blocking(&state.clone(), move || {
        // The state owns the other eye: found again here, inside the blocking job.
        let partner = state
            .stereo()
            .and_then(|s| s.partner.as_deref())
            .ok_or(missing)?;
        let (settings, ours) = parse_settings(&state, &body)?;
        let theirs = partner
            .prepare(&settings)
            .map_err(|e| ApiError::bad_request(format!("settings: {e}")))?;
        let (mine, other) = (state.shade(&ours), partner.shade(&theirs));
        let (left, right) = match eye {
            Eye::Left => (&mine, &other),
            Eye::Right => (&other, &mine),
        };
        encode::png(&shade::stereo::compose(layout, left, right))
            .map_err(|e| ApiError::internal(format!("encoding PNG: {e}")))
    })
    .await??;
    let headers = [
        (header::CONTENT_TYPE, HeaderValue::from_static("image/png")),
        (header::CACHE_CONTROL, HeaderValue::from_static("no-store")),
    ];
    Ok((headers, bytes).into_response())
}

async fn overlay(State(state): State<Arc<ViewerState>>, body: Bytes) -> Result<Response, ApiError> {
    blocking(&state.clone(), move || {
        let (_, shading) = parse_settings(&state, &body)?;
        let (w, h) = state.data.picture_size();
        let size = (u32::try_from(w), u32::try_from(h));
        let layer = match size {
            (Ok(w), Ok(h)) => shading.overlay(w, h),
            _ => None,
        };
        overlay_png(layer)
    })
    .await?
}

/// `?frame=N` (default 0).
#[derive(Deserialize)]
struct KeyframeQuery {
    #[serde(default)]
    frame: u32,
}

async fn keyframe(
    State(state): State<Arc<ViewerState>>,
    query: Result<Query<KeyframeQuery>, QueryRejection>,
    body: Bytes,
) -> Result<Response, ApiError> {
    let q = query_value("keyframe", query)?;
    let (settings, state) = blocking(&state.clone(), move || {
        let prepared = parse_settings(&state, &body);
        prepared.map(|(settings, _)| (settings, state))
    })
    .await??;
    let text = state.keyframe(q.frame, &settings);
    Ok(toml_download(text, attachment(&state, "keyframe.toml")))
}

/// `?col=C&row=R`.
#[derive(Deserialize)]
pub struct PixelQuery {
    pub col: usize,
    pub row: usize,
}

/// `GET /api/pixel`: the record of a pixel of `state`'s data file.
pub async fn pixel(
    State(state): State<Arc<ViewerState>>,
    query: Result<Query<PixelQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let q = query_value("pixel", query)?;
    let record = state.pixel(q.col, q.row).ok_or_else(|| {
        ApiError::bad_request(format!(
            "pixel ({}, {}) is outside the {}×{} image",
            q.col,
            q.row,
            state.data.picture_size().0,
            state.data.picture_size().1
        ))
    })?;
    Ok((no_store(), Json(record)).into_response())
}
