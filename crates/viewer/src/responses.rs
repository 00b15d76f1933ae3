//! The HTTP responses that carry pictures: raw RGBA for the page's canvas, PNG downloads
//! named after the scene, the overlay layer as an RGBA PNG. Shared by the shading routes and
//! the look routes.

use axum::body::Body;
use axum::http::{header, HeaderName, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use image::RgbaImage;

use crate::api_error::ApiError;
use crate::state::ViewerState;

/// The overlay layer ([`shade::layer`]) as an RGBA PNG, or 204 No Content when there is
/// nothing to draw; never cached.
pub fn overlay_png(layer: Option<RgbaImage>) -> Result<Response, ApiError> {
    let Some(layer) = layer else {
        return Ok((
            StatusCode::NO_CONTENT,
            [(header::CACHE_CONTROL, "no-store")],
        )
            .into_response());
    };
    let bytes = crate::encode::png_rgba(&layer)
        .map_err(|e| ApiError::internal(format!("encoding the overlay PNG: {e}")))?;
    let headers = [
        (header::CONTENT_TYPE, HeaderValue::from_static("image/png")),
        (header::CACHE_CONTROL, HeaderValue::from_static("no-store")),
    ];
    Ok((headers, bytes).into_response())
}

/// A picture as raw RGBA bytes, `width` × `height` in `X-Image-Width`, `X-Image-Height`;
/// never cached.
pub fn rgba_picture(bytes: Vec<u8>, width: u32, height: u32) -> Response {
    let headers = [
        (
            header::CONTENT_TYPE,
            HeaderValue::from_static("application/octet-stream"),
        ),
        (header::CACHE_CONTROL, HeaderValue::from_static("no-store")),
        (
            HeaderName::from_static("x-image-width"),
            HeaderValue::from(width),
        ),
        (
            HeaderName::from_static("x-image-height"),
            HeaderValue::from(height),
        ),
    ];
    (headers, bytes).into_response()
}

/// A file download of `content_type` named by `disposition` ([`attachment`],
/// [`attachment_named`]); never cached. Every download of the viewer is one of these.
pub fn download(
    body: impl Into<Body>,
    content_type: &'static str,
    disposition: HeaderValue,
) -> Response {
    let headers = [
        (header::CONTENT_TYPE, HeaderValue::from_static(content_type)),
        (header::CACHE_CONTROL, HeaderValue::from_static("no-store")),
        (header::CONTENT_DISPOSITION, disposition),
    ];
    (headers, body.into()).into_response()
}

/// A PNG file download.
pub fn png_download(bytes: Vec<u8>, disposition: HeaderValue) -> Response {
    download(bytes, "image/png", disposition)
}

/// A TOML text download (a keyframe, a flight's sequence script).
pub fn toml_download(text: String, disposition: HeaderValue) -> Response {
    download(text, "application/toml; charset=utf-8", disposition)
}

/// `attachment; filename="NAME"` for a download (the name is the scene's, made safe).
pub fn attachment(state: &ViewerState, extension: &str) -> HeaderValue {
    attachment_named(&state.data.header.scene_name, extension)
}

/// `attachment; filename="STEM.EXTENSION"`, the stem made safe (ASCII letters, digits, `-`
/// and `_`; `view` when nothing is left).
pub fn attachment_named(stem: &str, extension: &str) -> HeaderValue {
    let stem: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let stem = if stem.is_empty() {
        "view".to_string()
    } else {
        stem
    };
    HeaderValue::from_str(&format!("attachment; filename=\"{stem}.{extension}\"")).expect("ASCII")
}
