//! The routes that feed the page's WebGL2 shaders ([`crate::gpu`] says what each holds):
//!
//! | route | answer |
//! | --- | --- |
//! | `GET /api/gpu/channel/{name}` | one channel of the data file ([`crate::wire`] array) |
//! | `GET /api/gpu/textures` | each object's scene texture (JSON, [`crate::gpu::GpuTexture`]) |
//! | `GET /api/gpu/image/{name}` | an image texture, `earth` or `scene-K` (RGB8 array) |
//! | `GET /api/gpu/blackbody` | the black-body grid and the g·T table's layout (JSON) |
//! | `GET /api/gpu/blackbody/gt` | the g·T table's entries (f32 RGBA array) |
//!
//! The data never changes while the server runs; the page fetches each item once. Like every
//! route these pass [`crate::guard::check`]; the arrays are encoded within the server's bound
//! on concurrent work ([`crate::limit::WorkLimit`]: a data file's channel can be tens of MB),
//! and the image textures are the embedded scene's as the viewer loaded them, from the data
//! file's folder and the `--textures` folders only ([`shade::TextureSource`]).

use std::sync::{Arc, OnceLock};

use axum::extract::rejection::PathRejection;
use axum::extract::{Path, State};
use axum::http::{header, HeaderName, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::{Json, Router};
use shade::{ImageTexture, Texture};

use crate::api_error::{no_store, path_error, ApiError};
use crate::gpu::{self, Channel, GpuTexture};
use crate::state::ViewerState;

/// The GPU routes' state: the loaded file and its scene textures, loaded on first request.
pub struct GpuState {
    viewer: Arc<ViewerState>,
    textures: OnceLock<Result<Vec<Texture>, String>>,
}

impl GpuState {
    pub fn new(viewer: Arc<ViewerState>) -> GpuState {
        GpuState {
            viewer,
            textures: OnceLock::new(),
        }
    }

    /// The objects' scene textures, as the viewer loaded them when it loaded the file (which
    /// was refused if they could not be loaded from the allowed folders).
    fn scene_textures(&self) -> Result<&[Texture], ApiError> {
        let loaded = self
            .textures
            .get_or_init(|| self.viewer.scene_textures().map_err(|e| e.to_string()));
        loaded.as_deref().map_err(|e| ApiError::internal(e.clone()))
    }
}

/// The routes, with their own state; merged into [`crate::router`].
pub fn router(state: Arc<GpuState>) -> Router {
    Router::new()
        .route("/api/gpu/channel/{name}", get(channel))
        .route("/api/gpu/textures", get(textures))
        .route("/api/gpu/image/{name}", get(image))
        .route("/api/gpu/blackbody", get(blackbody))
        .route("/api/gpu/blackbody/gt", get(gt_table))
        .with_state(state)
}

/// A binary array answer.
pub fn array(bytes: Vec<u8>) -> Response {
    let headers = [
        (
            header::CONTENT_TYPE,
            HeaderValue::from_static("application/octet-stream"),
        ),
        (header::CACHE_CONTROL, HeaderValue::from_static("no-store")),
        (
            HeaderName::from_static("x-content-type-options"),
            HeaderValue::from_static("nosniff"),
        ),
    ];
    (headers, bytes).into_response()
}

async fn channel(
    State(state): State<Arc<GpuState>>,
    name: Result<Path<String>, PathRejection>,
) -> Result<Response, ApiError> {
    let Path(name) = name.map_err(|e| path_error("channel", e))?;
    let data = &state.viewer.data;
    let Some(channel) = Channel::parse(&name, data.lights.len()) else {
        let lights = (0..data.lights.len())
            .map(|k| format!(", light_{k}"))
            .collect::<String>();
        return Err(ApiError::new(
            StatusCode::NOT_FOUND,
            format!(
                "no channel '{name}' (this file has id, u, v, g, t_emit, cos_i, pol, dir{lights})"
            ),
        ));
    };
    let viewer = state.viewer.clone();
    let bytes = state
        .viewer
        .work()
        .admit()?
        .run(move || channel.encode(&viewer.data))
        .await?;
    Ok(array(bytes))
}

async fn textures(State(state): State<Arc<GpuState>>) -> Result<Response, ApiError> {
    let objects: Vec<GpuTexture> = state
        .scene_textures()?
        .iter()
        .enumerate()
        .map(|(k, t)| gpu::describe_texture(k, t))
        .collect();
    let body = serde_json::json!({ "objects": objects });
    Ok((no_store(), Json(body)).into_response())
}

async fn image(
    State(state): State<Arc<GpuState>>,
    name: Result<Path<String>, PathRejection>,
) -> Result<Response, ApiError> {
    let Path(name) = name.map_err(|e| path_error("image", e))?;
    let image = if name == gpu::EARTH {
        ImageTexture::earth().map_err(|e| ApiError::internal(e.to_string()))?
    } else {
        state
            .scene_textures()?
            .iter()
            .enumerate()
            .find_map(|(k, t)| match t {
                Texture::Image(image) if gpu::scene_image_name(k) == name => Some(image.clone()),
                _ => None,
            })
            .ok_or_else(|| ApiError::new(StatusCode::NOT_FOUND, format!("no image '{name}'")))?
    };
    let bytes = state
        .viewer
        .work()
        .admit()?
        .run(move || gpu::encode_image(&image))
        .await?;
    Ok(array(bytes))
}

async fn blackbody() -> Response {
    (no_store(), Json(gpu::blackbody())).into_response()
}

async fn gt_table() -> Response {
    array(gpu::encode_gt_table())
}
