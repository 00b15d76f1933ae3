//! [`ApiError`]: an error answer of the viewer's API, a status and a message sent to the page
//! as `{"error": "..."}`, never cached; and the refusals of what a request sent, naming it as
//! the request wrote it ([`json_body`], [`path_error`]).

use axum::extract::rejection::{PathRejection, QueryRejection};
use axum::extract::Query;
use axum::http::{header, HeaderName, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;

/// An error answer: a status and a message for the page.
#[derive(Clone, Debug)]
pub struct ApiError {
    pub status: StatusCode,
    pub message: String,
}

impl ApiError {
    pub fn new(status: StatusCode, message: impl Into<String>) -> ApiError {
        ApiError {
            status,
            message: message.into(),
        }
    }

    pub fn bad_request(message: impl Into<String>) -> ApiError {
        ApiError::new(StatusCode::BAD_REQUEST, message)
    }

    pub fn internal(message: impl Into<String>) -> ApiError {
        ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, message)
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = Json(serde_json::json!({ "error": self.message }));
        (self.status, no_store(), body).into_response()
    }
}

/// API answers change with every request: never cache them.
pub fn no_store() -> [(HeaderName, &'static str); 1] {
    [(header::CACHE_CONTROL, "no-store")]
}

/// A JSON request body of type `T`, refused (400) naming what the request wrote:
/// `NAME.FIELD: why` for a field (`view.camera.width`, `recording.keyframes[2].seconds`),
/// `NAME: why` for the body as a whole (not JSON, cut short, more after it). Where the body
/// ends or breaks before the parser knew which field it was in, the name stops at the last
/// field it knew (never a guessed `?`).
pub fn json_body<T: serde::de::DeserializeOwned>(body: &[u8], name: &str) -> Result<T, ApiError> {
    let mut json = serde_json::Deserializer::from_slice(body);
    let value = serde_path_to_error::deserialize(&mut json).map_err(|e| {
        let mut at = name.to_string();
        for segment in e.path().iter() {
            match segment {
                serde_path_to_error::Segment::Seq { index } => at += &format!("[{index}]"),
                serde_path_to_error::Segment::Map { key } => at += &format!(".{key}"),
                serde_path_to_error::Segment::Enum { variant } => at += &format!(".{variant}"),
                serde_path_to_error::Segment::Unknown => break,
            }
        }
        ApiError::bad_request(format!("{at}: {}", e.inner()))
    })?;
    json.end()
        .map_err(|e| ApiError::bad_request(format!("{name}: {e}")))?;
    Ok(value)
}

/// A route's query string as `T`, or a refusal as JSON naming the route: `NAME: why` (400, as
/// axum's own plain-text answer would say it). Every route reads its query through this.
pub fn query_value<T>(name: &str, query: Result<Query<T>, QueryRejection>) -> Result<T, ApiError> {
    query
        .map(|Query(value)| value)
        .map_err(|e| ApiError::bad_request(format!("{name}: {}", e.body_text())))
}

/// A path segment of a route that could not be read (`/api/explore/channel/%FF`), as JSON
/// like every other refusal (axum's own answer is plain text): `NAME: why`.
pub fn path_error(name: &str, rejection: PathRejection) -> ApiError {
    ApiError::new(
        rejection.status(),
        format!("{name}: {}", rejection.body_text()),
    )
}
