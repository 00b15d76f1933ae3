//! Looking around a full-sphere data file: the view the page starts from, and the pictures
//! of turned or boosted views made on the server with the `look` remapping and the
//! `shade` crate (what `godel look` then `godel shade` make), for saving and for checking
//! the page's shaders.
//!
//! | route | answer |
//! | --- | --- |
//! | `GET /api/view` | the file's camera and observer axes and velocity, whether it is a full sphere the page can look around in, and for a sphere the direction towards each object (JSON) |
//! | `POST /api/look/png` (`{"settings": …, "view": …}`) | the shaded picture of that view, PNG download |
//! | `POST /api/look/image` (same body) | the same picture as raw RGBA; `X-Image-Width`, `X-Image-Height` |
//! | `POST /api/look/overlay` (same body) | that picture's overlay layer (orientation marks of the view's camera, legend, labels) as an RGBA PNG, 204 when there is nothing to draw |
//!
//! A view is `{"camera": {"kind": "pinhole", "fov_deg": 60, "width": 640, "height": 360},
//! "forward": [x, y, z], "up": [x, y, z], "velocity": {"speed": 0.5, "direction": [x, y, z]}}`,
//! with the camera fields of a scene file (`h_fov_deg`, `v_fov_deg` for a panorama,
//! `fov_deg` for a pinhole or fisheye) and the axes in the moving observer's own frame, the
//! velocity in the static observer's, as in `godel look`; an optional `"samples": N` (a
//! square number, 1 if absent) reads N points per pixel. The sphere is read smoothly, as
//! `godel look` reads it by default (bilinear within one image of one object).
//!
//! Like every route these pass [`crate::guard::check`] (Host, Origin, JSON bodies within
//! [`crate::MAX_BODY_BYTES`]); a look picture is made within the server's bound on concurrent
//! work ([`crate::limit::WorkLimit`]) and has at most [`max_look_pixels`] samples (pixels
//! times samples per pixel), made in bands of rows so that its memory is its RGB bytes and a
//! band's records; its settings
//! are prepared as `/api/png`'s ([`ViewerState::prepare`]: caps on lamps and sources, image
//! textures only from the allowed folders).

use std::sync::{Arc, OnceLock};

use axum::body::Bytes;
use axum::extract::State;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use datafile::DataFile;
use look::{look_rows, samples_view, Filter, LookView, Sampling, SphereSource};
use scene::{Camera, Scene};
use serde::{Deserialize, Serialize};
use shade::{ShadeSettings, Shading};
use spacetime::LocalVelocity;

use crate::api_error::{json_body, no_store, ApiError};
use crate::encode;
use crate::state::ViewerState;

/// The most pixels of a look picture for `viewer`: the data file's own count, or a 4K
/// screen's (3840×2160) where that is more. A client cannot make the server hold more than
/// a few pictures' worth of records at once (the work limit bounds how many are made).
pub fn max_look_pixels(viewer: &ViewerState) -> u64 {
    (viewer.data.width as u64 * viewer.data.height as u64).max(3840 * 2160)
}

/// The look routes' state: the loaded file, and its object directions once computed.
pub struct LookState {
    viewer: Arc<ViewerState>,
    view: OnceLock<ViewInfo>,
}

impl LookState {
    pub fn new(viewer: Arc<ViewerState>) -> LookState {
        LookState {
            viewer,
            view: OnceLock::new(),
        }
    }
}

pub fn router(state: Arc<LookState>) -> Router {
    Router::new()
        .route("/api/view", get(view))
        .route("/api/look/png", post(png))
        .route("/api/look/image", post(image))
        .route("/api/look/overlay", post(overlay))
        .with_state(state)
}

/// A velocity as the page writes it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VelocityJson {
    pub speed: f64,
    pub direction: [f64; 3],
}

/// A view to look at: camera, axes in the moving observer's frame, velocity in the static
/// observer's frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewJson {
    pub camera: Camera,
    pub forward: [f64; 3],
    pub up: [f64; 3],
    pub velocity: VelocityJson,
    /// Samples per pixel of the look (a square number, `godel look --samples`); 1 if absent.
    #[serde(default = "one_sample")]
    pub samples: u32,
}

fn one_sample() -> u32 {
    1
}

/// `GET /api/view`.
#[derive(Clone, Debug, Serialize)]
pub struct ViewInfo {
    /// The file's own view.
    pub view: Option<ViewJson>,
    /// The page can look around: a full sphere traced by the static observer.
    pub sphere: bool,
    /// Why not, when it cannot.
    pub sphere_error: Option<String>,
    /// For a sphere, per object: the unit direction (static frame) of the mean of its
    /// pixels' directions weighted by their solid angle, `null` where it shows nowhere.
    pub object_directions: Vec<Option<[f64; 3]>>,
}

fn view_info(viewer: &ViewerState) -> ViewInfo {
    let data = &viewer.data;
    let read = Scene::read_view(&data.header.scene_text, "<scene embedded in the data file>");
    let view = read.as_ref().ok().map(|(observer, camera)| ViewJson {
        camera: *camera,
        forward: observer.forward,
        up: observer.up,
        velocity: VelocityJson {
            speed: observer.velocity.speed,
            direction: observer.velocity.direction,
        },
        samples: 1,
    });
    let (sphere, sphere_error, object_directions) = match (SphereSource::of(data), &read) {
        (Ok(_), Ok((observer, camera))) => {
            let k = data.header.object_names.len();
            let mut sums = vec![[0.0f64; 3]; k];
            for row in 0..data.height {
                for col in 0..data.width {
                    let r = &data.records[data.index(col, row)];
                    let Some(sum) = usize::try_from(r.object).ok().and_then(|o| sums.get_mut(o))
                    else {
                        continue;
                    };
                    if !r.is_hit() {
                        continue;
                    }
                    let Some(n) = observer.pixel_direction(camera, col as u32, row as u32) else {
                        continue;
                    };
                    // Solid angle of an equirectangular pixel ∝ cos(elevation).
                    let cos_el = (1.0 - n_dot(n, observer.up).powi(2)).max(0.0).sqrt();
                    for i in 0..3 {
                        sum[i] += cos_el * n[i];
                    }
                }
            }
            let dirs = sums
                .into_iter()
                .map(|s| {
                    let len = n_dot(s, s).sqrt();
                    (len > 0.0).then(|| s.map(|c| c / len))
                })
                .collect();
            (true, None, dirs)
        }
        (Err(e), _) => (false, Some(e.to_string()), Vec::new()),
        (_, Err(e)) => (false, Some(e.to_string()), Vec::new()),
    };
    ViewInfo {
        view,
        sphere,
        sphere_error,
        object_directions,
    }
}

fn n_dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

async fn view(State(state): State<Arc<LookState>>) -> Result<Response, ApiError> {
    let ticket = state.viewer.work().admit()?;
    let info = ticket
        .run(move || state.view.get_or_init(|| view_info(&state.viewer)).clone())
        .await?;
    Ok((no_store(), Json(info)).into_response())
}

/// The body of the look routes.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LookRequest {
    settings: ShadeSettings,
    view: ViewJson,
}

/// The requested view, checked, its sampling (smooth, with the view's samples per pixel), and
/// the settings prepared for it (orientation marks for the view's camera).
fn prepare_look(
    viewer: &ViewerState,
    body: &[u8],
) -> Result<(LookView, Sampling, Shading), ApiError> {
    let request: LookRequest = json_body(body, "look")?;
    let v = &request.view;
    let velocity = LocalVelocity::new(v.velocity.speed, v.velocity.direction).ok_or_else(|| {
        ApiError::bad_request(format!(
            "view: observer.velocity: speed must be in [0, 1) and the direction non-zero, \
             got {} along {:?}",
            v.velocity.speed, v.velocity.direction
        ))
    })?;
    let camera = v.camera;
    scene::samples_per_side(i64::from(v.samples), camera.width(), camera.height())
        .map_err(|m| ApiError::bad_request(format!("view: camera.samples: {m}")))?;
    let pixels = camera.width() as u64 * camera.height() as u64 * u64::from(v.samples);
    let most = max_look_pixels(viewer);
    if pixels > most {
        return Err(ApiError::bad_request(format!(
            "view: camera: {}×{} pixels × {} samples per pixel: {pixels} pixels to look up, more \
             than this viewer makes ({most}: the data file's own count or 3840×2160); use godel \
             look for larger pictures",
            camera.width(),
            camera.height(),
            v.samples
        )));
    }
    let sampling = Sampling {
        filter: Filter::Smooth,
        samples: v.samples,
    };
    let look_view = LookView::new(camera, v.forward, v.up, velocity)
        .map_err(|e| ApiError::bad_request(format!("view: {e}")))?;
    // Prepared for the loaded file: the looked file has the same objects, lights and event.
    let mut shading = viewer
        .prepare(&request.settings)
        .map_err(|e| ApiError::bad_request(format!("settings: {e}")))?;
    shading.mark_camera(&camera);
    Ok((look_view, sampling, shading))
}

/// Most samples of a look picture remapped at once: the picture is made in bands of rows,
/// each band's records (about 80 bytes a sample) shaded and dropped before the next, so a
/// 3840×2160 view takes its RGB bytes and about 20 MB of records at a time.
const BAND_PIXELS: usize = 1 << 18;

/// The picture of the requested view, shaded: look, then shade (its samples averaged), band
/// by band of rows (`look::look_rows`); the overlays drawn once over the whole.
fn shade_look(viewer: &ViewerState, body: &[u8]) -> Result<image::RgbImage, ApiError> {
    let (view, sampling, shading) = prepare_look(viewer, body)?;
    let bad = |e: look::LookError| ApiError::bad_request(format!("look: {e}"));
    let source = SphereSource::of(&viewer.data).map_err(bad)?;
    let (samples, s) = samples_view(&view, sampling.samples).map_err(bad)?;
    let (w, h) = (view.camera.width(), view.camera.height());
    let sample_row = w as usize * (s * s) as usize;
    let band = u32::try_from(BAND_PIXELS / sample_row.max(1))
        .unwrap_or(u32::MAX)
        .max(1);
    let mut rgb = Vec::with_capacity(w as usize * h as usize * 3);
    let mut rows = Vec::new();
    let mut header = viewer.data.header.clone();
    header.supersample = s;
    for start in (0..h).step_by(band as usize) {
        let end = start.saturating_add(band).min(h);
        let (records, lights) = look_rows(
            &viewer.data,
            &source,
            &samples,
            sampling.filter,
            s * start..s * end,
        );
        let part = DataFile {
            header: header.clone(),
            width: (w * s) as usize,
            height: ((end - start) * s) as usize,
            records,
            lights,
            polarization: viewer.data.polarization,
        };
        shading.image_rows_into(&part, &mut rows);
        rgb.extend_from_slice(&rows);
    }
    shading.draw_overlays(w as usize, h as usize, &mut rgb);
    image::RgbImage::from_raw(w, h, rgb)
        .ok_or_else(|| ApiError::internal("the look picture has the wrong size"))
}

async fn overlay(State(state): State<Arc<LookState>>, body: Bytes) -> Result<Response, ApiError> {
    let viewer = state.viewer.clone();
    let ticket = viewer.work().admit()?;
    ticket
        .run(move || {
            let (view, _, shading) = prepare_look(&viewer, &body)?;
            crate::responses::overlay_png(
                shading.overlay(view.camera.width(), view.camera.height()),
            )
        })
        .await?
}

async fn png(State(state): State<Arc<LookState>>, body: Bytes) -> Result<Response, ApiError> {
    let viewer = state.viewer.clone();
    let disposition = crate::responses::attachment(&viewer, "look.png");
    let ticket = viewer.work().admit()?;
    let bytes = ticket
        .run(move || {
            let img = shade_look(&viewer, &body)?;
            encode::png(&img).map_err(|e| ApiError::internal(format!("encoding PNG: {e}")))
        })
        .await??;
    Ok(crate::responses::png_download(bytes, disposition))
}

async fn image(State(state): State<Arc<LookState>>, body: Bytes) -> Result<Response, ApiError> {
    let viewer = state.viewer.clone();
    let ticket = viewer.work().admit()?;
    let img = ticket.run(move || shade_look(&viewer, &body)).await??;
    let bytes = encode::rgba_from_rgb(img.as_raw());
    Ok(crate::responses::rgba_picture(
        bytes,
        img.width(),
        img.height(),
    ))
}
