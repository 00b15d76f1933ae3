//! Orientation marks: where the camera looks, drawn on a picture as a faint grid of constant
//! azimuth and elevation with labelled ticks (`godel shade --grid`, `godel render --grid`,
//! the viewer's *grid* switch).
//!
//! Azimuth and elevation are those of [`scene::azimuth_elevation`] in the camera basis:
//! azimuth from `forward` toward `right`, elevation above the forward–right plane, in degrees.
//! Every position comes from the camera model's own inverse mapping
//! ([`scene::Camera::image_position`]), so a tick labelled 30° sits where
//! [`scene::Camera::pixel_direction`] looks at azimuth 30°:
//!
//! - panorama, sphere, pinhole: azimuth ticks on the top and bottom edges (azimuth is constant
//!   down a column for these cameras), labels above the bottom edge; elevation ticks on the
//!   left and right edges at the edge's own azimuth, labels beside the left edge;
//! - fisheye: azimuth ticks along the horizon (elevation 0, the horizontal diameter) and
//!   elevation ticks along the meridian of azimuth 0 (the vertical diameter), labelled beside
//!   them.
//!
//! The tick spacing is the smallest of 5°, 10°, 15°, 30°, 45°, 90° at which labels do not
//! overlap. The grid and the ticks are drawn into the RGBA overlay layer ([`crate::layer`]):
//! ticks opaque, grid lines translucent; the labels ([`mark_labels`]) are placed by the layer
//! with every other label, azimuths first, so that none overlaps another or leaves the
//! picture (a label that finds no room is left out; its tick stays).

use image::{Rgba, RgbaImage};
use scene::{azimuth_elevation, direction_from, Camera};

use crate::text::{fill, type_size, unit, Label};

/// Which angle a mark labels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    Azimuth,
    Elevation,
}

/// One tick: its angle and the pixel where it touches its edge (or, for the fisheye, the
/// pixel on the horizon or meridian it marks).
#[derive(Clone, Debug, PartialEq)]
pub struct Tick {
    pub axis: Axis,
    pub degrees: f64,
    pub col: u32,
    pub row: u32,
    pub label: String,
}

/// Colour of ticks and labels.
pub const MARK_COLOUR: [u8; 3] = [255, 255, 255];
/// Colour of the grid lines, with the opacity (35 %) they are blended at.
const GRID_COLOUR: [u8; 4] = [200, 220, 255, 89];
const STEPS: [f64; 6] = [5.0, 10.0, 15.0, 30.0, 45.0, 90.0];

/// The label of an angle: `30°`, `−45°` (with the minus sign U+2212).
fn label(deg: f64) -> String {
    let d = deg.round() as i64;
    if d < 0 {
        format!("−{}°", -d)
    } else {
        format!("{d}°")
    }
}

/// The widest label, whose width sets the azimuth spacing.
const WIDEST: &str = "−180°";

/// Angular extent (degrees) across the image horizontally and vertically.
fn spans(camera: &Camera) -> (f64, f64) {
    match *camera {
        Camera::Pinhole {
            fov_deg,
            width,
            height,
        } => {
            let t = (0.5 * fov_deg).to_radians().tan();
            let v = 2.0
                * (t * f64::from(height) / f64::from(width))
                    .atan()
                    .to_degrees();
            (fov_deg, v)
        }
        Camera::Panorama {
            h_fov_deg,
            v_fov_deg,
            ..
        } => (h_fov_deg, v_fov_deg),
        Camera::Sphere { .. } => (360.0, 180.0),
        Camera::Fisheye { fov_deg, .. } => (fov_deg, fov_deg),
    }
}

/// The smallest step whose ticks are at least `min_px` apart, given `px_per_deg`.
fn step(px_per_deg: f64, min_px: f64) -> f64 {
    STEPS
        .into_iter()
        .find(|s| s * px_per_deg >= min_px)
        .unwrap_or(90.0)
}

/// Multiples of `step` strictly inside (−half, half), and ±half itself when it is a multiple
/// below 180 (a panorama's edge).
fn multiples(step: f64, half: f64) -> Vec<f64> {
    let n = (half / step).floor() as i64;
    (-n..=n).map(|k| k as f64 * step).collect()
}

/// The pixel holding continuous image position (x, y), if inside the image.
fn pixel(camera: &Camera, x: f64, y: f64) -> Option<(u32, u32)> {
    let (w, h) = (f64::from(camera.width()), f64::from(camera.height()));
    // Positions exactly on the right or bottom border belong to the last pixel.
    let (x, y) = (x.min(w - 0.5), y.min(h - 0.5));
    (x >= 0.0 && y >= 0.0).then_some((x as u32, y as u32))
}

/// The labelled ticks for `camera` (sized as the picture they are drawn on).
pub fn ticks(camera: &Camera) -> Vec<Tick> {
    let (w, h) = (camera.width(), camera.height());
    let size = type_size(w, h);
    let widest = Label::new(WIDEST, size);
    let (h_span, v_span) = spans(camera);
    let label_px = (widest.width() + 4 * unit(size)) as f64;
    let az_step = step(f64::from(w) / h_span, label_px);
    let el_step = step(f64::from(h) / v_span, 1.5 * widest.height() as f64);
    let mut out = Vec::new();
    let mut push = |axis, degrees: f64, pos: Option<(f64, f64)>, edge_y: Option<f64>| {
        let Some((x, y)) = pos else { return };
        let y = edge_y.unwrap_or(y);
        if let Some((col, row)) = pixel(camera, x, y) {
            out.push(Tick {
                axis,
                degrees,
                col,
                row,
                label: label(degrees),
            });
        }
    };
    match camera {
        Camera::Fisheye { .. } => {
            let half = (0.5 * h_span).min(180.0);
            for a in multiples(az_step, half) {
                let pos = camera.image_position(direction_from(a, 0.0));
                push(Axis::Azimuth, a, pos, None);
            }
            for e in multiples(el_step, (0.5 * v_span).min(90.0)) {
                if e != 0.0 {
                    let pos = camera.image_position(direction_from(0.0, e));
                    push(Axis::Elevation, e, pos, None);
                }
            }
        }
        _ => {
            let half = (0.5 * h_span).min(180.0);
            for a in multiples(az_step, half) {
                // Azimuth is constant down a column: the tick stands on the bottom edge.
                let pos = camera.image_position(direction_from(a, 0.0));
                push(Axis::Azimuth, a, pos, Some(f64::from(h)));
            }
            // The left edge's own azimuth (direction_at on the border, mid-height).
            let Some(edge) = camera.direction_at(0.0, 0.5 * f64::from(h)) else {
                return out;
            };
            let (left_az, _) = azimuth_elevation(edge);
            for e in multiples(el_step, (0.5 * v_span).min(90.0)) {
                let pos = camera
                    .image_position(direction_from(left_az, e))
                    .map(|(_, y)| (0.0, y));
                push(Axis::Elevation, e, pos, None);
            }
        }
    }
    out
}

/// The camera a data file was traced with, sized to the data file's image: the `[camera]`
/// of the scene embedded in its header (`None` if that does not read as a camera).
pub fn data_camera(data: &datafile::DataFile) -> Option<Camera> {
    let camera = scene::camera_from_str(&data.header.scene_text, "embedded scene").ok()?;
    let w = u32::try_from(data.width).ok()?;
    let h = u32::try_from(data.height).ok()?;
    Some(camera.with_size(w, h))
}

/// Azimuth and elevation (degrees, camera basis) where pixel (col, row) of a picture made
/// with `camera` looks; `None` for pixels the camera does not trace. What the viewer shows
/// under the mouse.
pub fn pixel_angles(camera: &Camera, col: u32, row: u32) -> Option<(f64, f64)> {
    camera.pixel_direction(col, row).map(azimuth_elevation)
}

/// Puts the translucent grid colour at pixel (x, y) if it is inside the image.
fn grid_pixel(img: &mut RgbaImage, x: f64, y: f64) {
    if x < 0.0 || y < 0.0 || x >= f64::from(img.width()) || y >= f64::from(img.height()) {
        return;
    }
    img.put_pixel(x as u32, y as u32, Rgba(GRID_COLOUR));
}

/// Draws the faint grid lines of the ticks' azimuths and elevations: each line sampled at
/// most half a pixel apart and mapped through [`Camera::image_position`].
fn draw_grid(img: &mut RgbaImage, camera: &Camera, ticks: &[Tick]) {
    let (w, h) = (f64::from(camera.width()), f64::from(camera.height()));
    let (h_span, v_span) = spans(camera);
    let px_per_deg = (w / h_span).max(h / v_span).max(1e-3);
    let d = (0.5 / px_per_deg).clamp(1e-3, 0.5);
    let n = (360.0 / d).ceil().min(2e6) as usize;
    let mut seen = std::collections::HashSet::new();
    for t in ticks {
        for k in 0..=n {
            let s = -180.0 + k as f64 * d;
            let dir = match t.axis {
                Axis::Azimuth if s.abs() <= 90.0 => direction_from(t.degrees, s),
                Axis::Elevation => direction_from(s, t.degrees),
                Axis::Azimuth => continue,
            };
            if let Some((x, y)) = camera.image_position(dir) {
                // One visit per pixel (crossings and dense samples).
                if x >= 0.0 && y >= 0.0 && seen.insert((x as u32, y as u32)) {
                    grid_pixel(img, x, y);
                }
            }
        }
    }
}

/// Length in pixels of a tick at type size `size`.
fn tick_length(size: f32) -> i64 {
    4 * unit(size) + 2
}

/// Height in pixels of the band along the bottom edge that the azimuth ticks and labels of
/// a `width`×`height` picture made with `camera` occupy (0 for a fisheye, whose labels run
/// along the horizon): where the layer puts the legend above.
pub fn bottom_band(camera: &Camera, width: u32, height: u32) -> u32 {
    if matches!(camera, Camera::Fisheye { .. }) || width < 16 || height < 16 {
        return 0;
    }
    let size = type_size(width, height);
    let u = unit(size);
    (tick_length(size) + u + Label::new("0°", size).height() + u) as u32
}

/// Draws the grid and the ticks into `img`, the overlay layer of a picture made with
/// `camera`'s geometry at any size (the camera is resized to the layer). Pictures under
/// 16×16 pixels get no marks.
pub fn draw_grid_and_ticks(img: &mut RgbaImage, camera: &Camera) {
    let (w, h) = (img.width(), img.height());
    if w < 16 || h < 16 {
        return;
    }
    let camera = camera.with_size(w, h);
    let ticks = ticks(&camera);
    draw_grid(img, &camera, &ticks);
    let size = type_size(w, h);
    let s = unit(size);
    let len = tick_length(size);
    let (wi, hi) = (i64::from(w), i64::from(h));
    let fisheye = matches!(camera, Camera::Fisheye { .. });
    for t in &ticks {
        let (x, y) = (i64::from(t.col), i64::from(t.row));
        match (t.axis, fisheye) {
            (Axis::Azimuth, false) => {
                fill(img, x - s / 2, hi - len, s, len, MARK_COLOUR);
                fill(img, x - s / 2, 0, s, len, MARK_COLOUR);
            }
            (Axis::Elevation, false) => {
                fill(img, 0, y - s / 2, len, s, MARK_COLOUR);
                fill(img, wi - len, y - s / 2, len, s, MARK_COLOUR);
            }
            (Axis::Azimuth, true) => fill(img, x - s / 2, y - len / 2, s, len, MARK_COLOUR),
            (Axis::Elevation, true) => fill(img, x - len / 2, y - s / 2, len, s, MARK_COLOUR),
        }
    }
}

/// A label of the marks and where it would go: the top-left corner of its box.
#[derive(Clone, Debug)]
pub struct MarkLabel {
    pub axis: Axis,
    pub label: Label,
    pub x: i64,
    pub y: i64,
}

/// The labels of the ticks of `camera` on a `width` × `height` picture, azimuths first, each
/// beside its tick: azimuths above the bottom ticks (a fisheye's below its horizon ticks),
/// elevations right of the left ticks (of its meridian ticks), moved inside the picture
/// where they would stick out; elevation labels that would reach into the band of the
/// azimuth labels ([`bottom_band`]) are left out, so that no elevation reads as an azimuth.
/// Empty under 16×16 pixels.
pub fn mark_labels(camera: &Camera, width: u32, height: u32) -> Vec<MarkLabel> {
    if width < 16 || height < 16 {
        return Vec::new();
    }
    let camera = camera.with_size(width, height);
    let size = type_size(width, height);
    let s = unit(size);
    let len = tick_length(size);
    let (wi, hi) = (i64::from(width), i64::from(height));
    let fisheye = matches!(camera, Camera::Fisheye { .. });
    let band = i64::from(bottom_band(&camera, width, height));
    let mut ticks = ticks(&camera);
    ticks.sort_by_key(|t| t.axis == Axis::Elevation);
    ticks
        .into_iter()
        .filter_map(|t| {
            let label = Label::new(&t.label, size);
            let (lw, lh) = (label.width(), label.height());
            let (x, y) = (i64::from(t.col), i64::from(t.row));
            let centred_x = (x - lw / 2).clamp(0, (wi - lw).max(0));
            let centred_y = (y - lh / 2).clamp(0, (hi - lh).max(0));
            let (x, y) = match (t.axis, fisheye) {
                (Axis::Azimuth, false) => (centred_x, hi - len - s - lh),
                (Axis::Elevation, false) => (len + s, centred_y),
                (Axis::Azimuth, true) => (centred_x, (y + len / 2 + s).min(hi - lh)),
                (Axis::Elevation, true) => (x + len / 2 + s, centred_y),
            };
            let in_band = t.axis == Axis::Elevation && y + lh > hi - band;
            (!in_band).then_some(MarkLabel {
                axis: t.axis,
                label,
                x,
                y,
            })
        })
        .collect()
}
