//! Cameras: which direction each pixel looks along, exactly as fixed in docs/physics.md
//! ("Pixels and cameras"), so that every tool reads pixels the same way.
//!
//! Directions are returned in the *camera basis*: components along (forward, right, up),
//! with right = forward × up. [`crate::Observer::pixel_direction`] turns them into the
//! observer's local-frame components. Pixel (col, row) has its centre at (col + ½, row + ½);
//! row 0 is the top row. Sub-pixel samples are the pixels of [`Camera::supersampled`]
//! (docs/physics.md, "Pixels and cameras").

use serde::{Deserialize, Serialize};

/// Largest image side, and largest pixel count: guards against typos that would allocate
/// gigabytes.
pub const MAX_SIDE: u32 = 20_000;
pub const MAX_PIXELS: u64 = 50_000_000;

/// The closed set of cameras. Field-of-view angles are in degrees; values are validated
/// when a scene is read, or with [`Camera::check`] (pinhole fov in (0, 180), panorama h_fov
/// in (0, 360] and v_fov in (0, 180], fisheye fov in (0, 360], sizes in 1..=[`MAX_SIDE`],
/// at most [`MAX_PIXELS`] pixels).
///
/// Its JSON form (the viewer's page reads and writes it) is the scene file's `[camera]`
/// table without `samples`: `{"kind": "fisheye", "fov_deg": 180, "width": 512, "height": 512}`;
/// a fisheye's `width` and `height` must be equal.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Camera {
    /// Image plane at unit distance, horizontal field of view `fov_deg`, square pixels.
    Pinhole {
        fov_deg: f64,
        width: u32,
        height: u32,
    },
    /// Equirectangular: azimuth linear in column, elevation linear in row.
    Panorama {
        h_fov_deg: f64,
        v_fov_deg: f64,
        width: u32,
        height: u32,
    },
    /// The full sphere: a 360°×180° panorama.
    Sphere { width: u32, height: u32 },
    /// Equidistant fisheye (dome master) on a square `size`×`size` image; the inscribed
    /// circle spans `fov_deg`.
    #[serde(
        serialize_with = "square_json::serialize",
        deserialize_with = "square_json::deserialize"
    )]
    Fisheye { fov_deg: f64, size: u32 },
}

/// The fisheye's JSON form: `size` written as the `width` and `height` of every other camera.
mod square_json {
    use serde::{de::Error, Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Square {
        fov_deg: f64,
        width: u32,
        height: u32,
    }

    pub fn serialize<S: Serializer>(fov_deg: &f64, size: &u32, s: S) -> Result<S::Ok, S::Error> {
        Square {
            fov_deg: *fov_deg,
            width: *size,
            height: *size,
        }
        .serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<(f64, u32), D::Error> {
        let q = Square::deserialize(d)?;
        match super::Camera::fisheye(q.fov_deg, q.width, q.height) {
            Ok(_) => Ok((q.fov_deg, q.width)),
            Err((field, message)) => Err(D::Error::custom(format!("{field}: {message}"))),
        }
    }
}

impl Camera {
    /// A fisheye of `fov_deg` on a `width` × `height` image, which must be square. The error
    /// names the scene-file field, as [`Camera::check`]'s does.
    pub fn fisheye(
        fov_deg: f64,
        width: u32,
        height: u32,
    ) -> Result<Camera, (&'static str, String)> {
        if width != height {
            return Err((
                "camera.height",
                format!(
                    "a fisheye image is square: height must equal width ({width}), got {height}"
                ),
            ));
        }
        Ok(Camera::Fisheye {
            fov_deg,
            size: width,
        })
    }

    pub fn width(&self) -> u32 {
        match *self {
            Camera::Pinhole { width, .. }
            | Camera::Panorama { width, .. }
            | Camera::Sphere { width, .. } => width,
            Camera::Fisheye { size, .. } => size,
        }
    }

    pub fn height(&self) -> u32 {
        match *self {
            Camera::Pinhole { height, .. }
            | Camera::Panorama { height, .. }
            | Camera::Sphere { height, .. } => height,
            Camera::Fisheye { size, .. } => size,
        }
    }

    /// The kind as written in scene files.
    pub fn kind(&self) -> &'static str {
        match self {
            Camera::Pinhole { .. } => "pinhole",
            Camera::Panorama { .. } => "panorama",
            Camera::Sphere { .. } => "sphere",
            Camera::Fisheye { .. } => "fisheye",
        }
    }

    /// A one-line description, e.g. `panorama 220°×25°, 880×100`.
    pub fn describe(&self) -> String {
        let (w, h) = (self.width(), self.height());
        match *self {
            Camera::Pinhole { fov_deg, .. } => format!("pinhole {fov_deg}°, {w}×{h}"),
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                ..
            } => format!("panorama {h_fov_deg}°×{v_fov_deg}°, {w}×{h}"),
            Camera::Sphere { .. } => format!("sphere 360°×180°, {w}×{h}"),
            Camera::Fisheye { fov_deg, .. } => format!("fisheye {fov_deg}°, {w}×{h}"),
        }
    }

    /// Checks sizes and angles (the limits in the type's documentation). The error names
    /// the scene-file field, e.g. `("camera.fov_deg", "must be in (0, 180) degrees, got 180")`.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        let (width, height) = (self.width(), self.height());
        for (field, v) in [("camera.width", width), ("camera.height", height)] {
            if v == 0 || v > MAX_SIDE {
                return Err((field, format!("must be in 1..={MAX_SIDE}, got {v}")));
            }
        }
        let pixels = width as u64 * height as u64;
        if pixels > MAX_PIXELS {
            return Err((
                "camera.height",
                format!("image has {pixels} pixels, more than the limit of {MAX_PIXELS}"),
            ));
        }
        let angle = |field: &'static str, v: f64, max: f64, max_inclusive: bool| {
            if !v.is_finite() {
                return Err((field, format!("must be a finite number, got {v}")));
            }
            let ok = v > 0.0 && if max_inclusive { v <= max } else { v < max };
            if ok {
                Ok(())
            } else {
                let close = if max_inclusive { "]" } else { ")" };
                Err((
                    field,
                    format!(
                        "must be in (0, {max}{close} degrees, got {}",
                        crate::short(v)
                    ),
                ))
            }
        };
        match *self {
            Camera::Pinhole { fov_deg, .. } => angle("camera.fov_deg", fov_deg, 180.0, false),
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                ..
            } => {
                angle("camera.h_fov_deg", h_fov_deg, 360.0, true)?;
                angle("camera.v_fov_deg", v_fov_deg, 180.0, true)
            }
            Camera::Sphere { .. } => Ok(()),
            Camera::Fisheye { fov_deg, .. } => angle("camera.fov_deg", fov_deg, 360.0, true),
        }
    }

    /// Unit direction in the camera basis (forward, right, up) for pixel (col, row);
    /// `None` outside the image or, for the fisheye, outside the inscribed circle.
    pub fn pixel_direction(&self, col: u32, row: u32) -> Option<[f64; 3]> {
        if col >= self.width() || row >= self.height() {
            return None;
        }
        self.direction_at(col as f64 + 0.5, row as f64 + 0.5)
    }

    /// Unit direction in the camera basis for the continuous image position (x, y) in pixel
    /// units, (0, 0) the top-left corner of the image and (col + ½, row + ½) the centre of
    /// pixel (col, row); `None` for the fisheye outside its circle. Positions outside the
    /// image are extrapolated (the marks use them for ticks on the border).
    pub fn direction_at(&self, x: f64, y: f64) -> Option<[f64; 3]> {
        let (w, h) = (self.width() as f64, self.height() as f64);
        match *self {
            Camera::Pinhole { fov_deg, .. } => {
                let t = (0.5 * fov_deg).to_radians().tan();
                let x = t * (2.0 * x / w - 1.0);
                let y = t * (h / w) * (1.0 - 2.0 * y / h);
                let n = (1.0 + x * x + y * y).sqrt();
                Some([1.0 / n, x / n, y / n])
            }
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                ..
            } => Some(panorama(h_fov_deg, v_fov_deg, x / w, y / h)),
            Camera::Sphere { .. } => Some(panorama(360.0, 180.0, x / w, y / h)),
            Camera::Fisheye { fov_deg, .. } => {
                // Offsets from the centre in units of the circle's radius: right and up.
                let dx = 2.0 * x / w - 1.0;
                let dy = 1.0 - 2.0 * y / h;
                let rho = dx.hypot(dy);
                if rho > 1.0 {
                    return None;
                }
                let theta = rho * (0.5 * fov_deg).to_radians();
                // Position angle ψ from up, increasing toward right: (sin ψ, cos ψ) = (dx, dy)/ρ.
                let (sin_psi, cos_psi) = if rho > 0.0 {
                    (dx / rho, dy / rho)
                } else {
                    (0.0, 1.0)
                };
                let (s, c) = theta.sin_cos();
                Some([c, s * sin_psi, s * cos_psi])
            }
        }
    }

    /// The inverse of [`Camera::direction_at`]: the continuous image position (x, y) at which
    /// the camera looks along `d` (camera basis, any length), or `None` where it does not look
    /// that way (behind a pinhole, outside a panorama's field or a fisheye's circle, the zero
    /// vector). The one home of the inverse mapping: orientation marks and the viewer's
    /// direction readout both go through [`Camera::direction_at`] and this.
    pub fn image_position(&self, d: [f64; 3]) -> Option<(f64, f64)> {
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(n.is_finite() && n > 0.0) {
            return None;
        }
        let d = [d[0] / n, d[1] / n, d[2] / n];
        let (w, h) = (self.width() as f64, self.height() as f64);
        let (x, y) = match *self {
            Camera::Pinhole { fov_deg, .. } => {
                if d[0] <= 0.0 {
                    return None;
                }
                let t = (0.5 * fov_deg).to_radians().tan();
                let (px, py) = (d[1] / d[0], d[2] / d[0]);
                (0.5 * w * (px / t + 1.0), 0.5 * h * (1.0 - py / (t * h / w)))
            }
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                ..
            } => panorama_inverse(h_fov_deg, v_fov_deg, d, w, h)?,
            Camera::Sphere { .. } => panorama_inverse(360.0, 180.0, d, w, h)?,
            Camera::Fisheye { fov_deg, .. } => {
                let theta = d[0].clamp(-1.0, 1.0).acos();
                let rho = theta / (0.5 * fov_deg).to_radians();
                if rho > 1.0 + 1e-12 {
                    return None;
                }
                let s = d[1].hypot(d[2]);
                let (sin_psi, cos_psi) = if s > 0.0 {
                    (d[1] / s, d[2] / s)
                } else {
                    (0.0, 1.0)
                };
                (
                    0.5 * w * (rho * sin_psi + 1.0),
                    0.5 * h * (1.0 - rho * cos_psi),
                )
            }
        };
        Some((x, y))
    }

    /// The same camera with another image size (the fisheye takes `width`): the geometry of
    /// a picture shown at another resolution than it was traced.
    pub fn with_size(&self, width: u32, height: u32) -> Camera {
        match *self {
            Camera::Pinhole { fov_deg, .. } => Camera::Pinhole {
                fov_deg,
                width,
                height,
            },
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                ..
            } => Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                width,
                height,
            },
            Camera::Sphere { .. } => Camera::Sphere { width, height },
            Camera::Fisheye { fov_deg, .. } => Camera::Fisheye {
                fov_deg,
                size: width,
            },
        }
    }
}

/// Azimuth and elevation in degrees of a direction in the camera basis (forward, right, up):
/// azimuth from forward toward right in (−180°, 180°], elevation above the forward–right
/// plane in [−90°, 90°].
pub fn azimuth_elevation(d: [f64; 3]) -> (f64, f64) {
    let horizontal = d[0].hypot(d[1]);
    (
        d[1].atan2(d[0]).to_degrees(),
        d[2].atan2(horizontal).to_degrees(),
    )
}

/// The unit direction (camera basis) at azimuth `az_deg` and elevation `el_deg`
/// (the inverse of [`azimuth_elevation`]).
pub fn direction_from(az_deg: f64, el_deg: f64) -> [f64; 3] {
    let (sa, ca) = az_deg.to_radians().sin_cos();
    let (sb, cb) = el_deg.to_radians().sin_cos();
    [cb * ca, cb * sa, sb]
}

/// Image position of direction `d` (unit) in a panorama spanning `h_fov`×`v_fov` degrees,
/// `None` outside the field.
fn panorama_inverse(h_fov: f64, v_fov: f64, d: [f64; 3], w: f64, h: f64) -> Option<(f64, f64)> {
    let (az, el) = azimuth_elevation(d);
    let u = az / h_fov + 0.5;
    let v = 0.5 - el / v_fov;
    let eps = 1e-12;
    if !(-eps..=1.0 + eps).contains(&u) || !(-eps..=1.0 + eps).contains(&v) {
        return None;
    }
    Some((u * w, v * h))
}

/// Most rays per pixel (`[camera] samples`, `godel render --samples`): 16×16.
pub const MAX_SAMPLES: u32 = 256;
/// Most rays per image, samples included: each ray keeps its record in memory and in the
/// data file (~150 bytes while writing), so this bounds memory as the pixel limit does.
pub const MAX_RAYS: u64 = 50_000_000;

/// Checks a rays-per-pixel count for a `width` × `height` image: a square number s² in
/// 1..=[`MAX_SAMPLES`] with width · height · s² ≤ [`MAX_RAYS`]; returns s, the samples per
/// pixel along each side. The message names no field (the caller does).
pub fn samples_per_side(samples: i64, width: u32, height: u32) -> Result<u32, String> {
    if !(1..=i64::from(MAX_SAMPLES)).contains(&samples) {
        return Err(format!(
            "must be in 1..={MAX_SAMPLES} rays per pixel, got {samples}"
        ));
    }
    let side = (samples as f64).sqrt().round() as u32;
    if i64::from(side * side) != samples {
        return Err(format!(
            "must be a square number (1, 4, 9, 16, …: s×s rays on a grid in each pixel), got {samples}"
        ));
    }
    let rays = u64::from(width) * u64::from(height) * samples as u64;
    if rays > MAX_RAYS {
        return Err(format!(
            "{width}×{height} pixels × {samples} samples = {rays} rays, more than the limit of {MAX_RAYS}"
        ));
    }
    Ok(side)
}

impl Camera {
    /// The camera whose pixels are the `s`×`s` samples of this camera's pixels: the same
    /// view with width and height multiplied by `s`. Its pixel (s·col + i, s·row + j) has
    /// its centre at (col + (i + ½)/s, row + (j + ½)/s) of this camera, so
    /// [`Camera::pixel_direction`] of the result is the sub-pixel direction (stratified on a
    /// regular grid), and a render with s×s samples traces exactly the rays of a render s
    /// times larger.
    pub fn supersampled(&self, s: u32) -> Camera {
        let s = s.max(1);
        match *self {
            Camera::Pinhole {
                fov_deg,
                width,
                height,
            } => Camera::Pinhole {
                fov_deg,
                width: width * s,
                height: height * s,
            },
            Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                width,
                height,
            } => Camera::Panorama {
                h_fov_deg,
                v_fov_deg,
                width: width * s,
                height: height * s,
            },
            Camera::Sphere { width, height } => Camera::Sphere {
                width: width * s,
                height: height * s,
            },
            Camera::Fisheye { fov_deg, size } => Camera::Fisheye {
                fov_deg,
                size: size * s,
            },
        }
    }
}

/// Panorama direction at fractional image position (u, v) ∈ (0, 1)², v = 0 at the top.
fn panorama(h_fov_deg: f64, v_fov_deg: f64, u: f64, v: f64) -> [f64; 3] {
    let alpha = h_fov_deg.to_radians() * (u - 0.5);
    let beta = v_fov_deg.to_radians() * (0.5 - v);
    let (sa, ca) = alpha.sin_cos();
    let (sb, cb) = beta.sin_cos();
    [cb * ca, cb * sa, sb]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
    }
    fn norm(d: [f64; 3]) -> f64 {
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    }

    fn cameras() -> Vec<Camera> {
        vec![
            Camera::Pinhole {
                fov_deg: 90.0,
                width: 101,
                height: 51,
            },
            Camera::Panorama {
                h_fov_deg: 220.0,
                v_fov_deg: 25.0,
                width: 881,
                height: 101,
            },
            Camera::Sphere {
                width: 361,
                height: 181,
            },
            Camera::Fisheye {
                fov_deg: 180.0,
                size: 101,
            },
        ]
    }

    #[test]
    fn samples_are_the_pixels_of_the_supersampled_camera_at_sub_pixel_centres() {
        for c in cameras() {
            let s = 3;
            let fine = c.supersampled(s);
            assert_eq!(
                (fine.width(), fine.height()),
                (c.width() * s, c.height() * s)
            );
            // The middle sample of each pixel (odd s) is the pixel's centre.
            for (col, row) in [(0, 0), (c.width() / 2, c.height() / 2), (7, 5)] {
                let centre = c.pixel_direction(col, row);
                let middle = fine.pixel_direction(s * col + 1, s * row + 1);
                match (centre, middle) {
                    (Some(a), Some(b)) => assert!(close(a, b), "{c:?} ({col}, {row})"),
                    (a, b) => assert_eq!(a.is_some(), b.is_some(), "{c:?} ({col}, {row})"),
                }
            }
        }
    }

    #[test]
    fn sample_counts_are_square_and_bounded() {
        assert_eq!(samples_per_side(1, 10, 10), Ok(1));
        assert_eq!(samples_per_side(16, 10, 10), Ok(4));
        assert_eq!(samples_per_side(256, 10, 10), Ok(16));
        for bad in [0, -4, 2, 15, 257, 1024] {
            assert!(samples_per_side(bad, 10, 10).is_err(), "{bad}");
        }
        assert!(samples_per_side(16, 5000, 1000).is_err()); // 8·10⁷ rays
    }

    #[test]
    fn centre_pixel_looks_forward() {
        for c in cameras() {
            let d = c.pixel_direction(c.width() / 2, c.height() / 2).unwrap();
            assert!(close(d, [1.0, 0.0, 0.0]), "{c:?}: {d:?}");
        }
    }

    #[test]
    fn left_right_and_up_down_are_mirror_images() {
        for c in cameras() {
            let (w, h) = (c.width(), c.height());
            for (col, row) in [(0, 0), (3, 7), (w / 4, h / 3), (w - 1, h / 2)] {
                let (Some(d), Some(m)) = (
                    c.pixel_direction(col, row),
                    c.pixel_direction(w - 1 - col, row),
                ) else {
                    continue;
                };
                assert!(close(d, [m[0], -m[1], m[2]]), "{c:?} lr {col},{row}");
                let m = c.pixel_direction(col, h - 1 - row).unwrap();
                assert!(close(d, [m[0], m[1], -m[2]]), "{c:?} ud {col},{row}");
            }
        }
    }

    #[test]
    fn right_is_right_and_top_is_up() {
        for c in cameras() {
            let (w, h) = (c.width(), c.height());
            assert!(c.pixel_direction(w - 1, h / 2).unwrap()[1] > 0.0);
            assert!(c.pixel_direction(w / 2, 0).unwrap()[2] > 0.0);
        }
    }

    #[test]
    fn directions_are_unit() {
        for c in cameras() {
            for row in (0..c.height()).step_by(7) {
                for col in (0..c.width()).step_by(5) {
                    if let Some(d) = c.pixel_direction(col, row) {
                        assert!((norm(d) - 1.0).abs() < 1e-12);
                    }
                }
            }
        }
    }

    #[test]
    fn panorama_edge_azimuths() {
        let (w, h) = (880, 100);
        let c = Camera::Panorama {
            h_fov_deg: 220.0,
            v_fov_deg: 25.0,
            width: w,
            height: h,
        };
        let half_pixel = 220.0 / w as f64 / 2.0;
        let az = |d: [f64; 3]| d[1].atan2(d[0]).to_degrees();
        let el = |d: [f64; 3]| d[2].asin().to_degrees();
        let left = c.pixel_direction(0, h / 2).unwrap();
        let right = c.pixel_direction(w - 1, h / 2).unwrap();
        assert!((az(left) - (-110.0 + half_pixel)).abs() < 1e-9);
        assert!((az(right) - (110.0 - half_pixel)).abs() < 1e-9);
        let top = c.pixel_direction(w / 2, 0).unwrap();
        assert!((el(top) - (12.5 - 25.0 / h as f64 / 2.0)).abs() < 1e-9);
    }

    #[test]
    fn pinhole_edges_match_tangent_plane() {
        let c = Camera::Pinhole {
            fov_deg: 90.0,
            width: 100,
            height: 50,
        };
        let d = c.pixel_direction(99, 25).unwrap();
        // x = tan 45°·(2·99.5/100 − 1) = 0.99, y = 0.5·(1 − 2·25.5/50) = −0.01.
        assert!((d[1] / d[0] - 0.99).abs() < 1e-12);
        assert!((d[2] / d[0] + 0.01).abs() < 1e-12);
    }

    #[test]
    fn fisheye_radius_is_proportional_to_angle() {
        let n = 200;
        let c = Camera::Fisheye {
            fov_deg: 180.0,
            size: n,
        };
        for col in [100, 120, 150, 180, 199] {
            let d = c.pixel_direction(col, 100).unwrap();
            // Pixel centre's distance from the image centre, in units of the radius.
            let rho = ((col as f64 + 0.5 - 100.0).powi(2) + 0.25).sqrt() / 100.0;
            let angle = d[0].clamp(-1.0, 1.0).acos();
            assert!((angle - rho * 90f64.to_radians()).abs() < 1e-12);
        }
        // Corners lie outside the inscribed circle.
        assert!(c.pixel_direction(0, 0).is_none());
        assert!(c.pixel_direction(n - 1, n - 1).is_none());
        // Position angle: straight up at the top, straight right at the right edge.
        let up = c.pixel_direction(100, 0).unwrap();
        assert!(up[2] > 0.99 * (89f64).to_radians().sin() && up[1].abs() < 0.01);
    }

    #[test]
    fn outside_the_image_is_none() {
        for c in cameras() {
            assert!(c.pixel_direction(c.width(), 0).is_none());
            assert!(c.pixel_direction(0, c.height()).is_none());
        }
    }

    #[test]
    fn a_fisheye_is_square() {
        assert_eq!(
            Camera::fisheye(180.0, 64, 64),
            Ok(Camera::Fisheye {
                fov_deg: 180.0,
                size: 64
            })
        );
        let (field, message) = Camera::fisheye(180.0, 64, 65).unwrap_err();
        assert_eq!(field, "camera.height");
        assert!(
            message.contains("must equal width (64), got 65"),
            "{message}"
        );
    }

    #[test]
    fn describe_names_the_kind() {
        let c = Camera::Panorama {
            h_fov_deg: 220.0,
            v_fov_deg: 25.0,
            width: 880,
            height: 100,
        };
        assert_eq!(c.describe(), "panorama 220°×25°, 880×100");
    }

    #[test]
    fn image_position_inverts_direction_at() {
        for c in cameras() {
            let (w, h) = (c.width(), c.height());
            for row in (0..h).step_by(3) {
                for col in (0..w).step_by(7) {
                    let Some(d) = c.pixel_direction(col, row) else {
                        continue;
                    };
                    let (x, y) = c.image_position(d).expect("a traced pixel maps back");
                    assert!(
                        (x - (col as f64 + 0.5)).abs() < 1e-7
                            && (y - (row as f64 + 0.5)).abs() < 1e-7,
                        "{c:?} {col},{row}: {x},{y}"
                    );
                }
            }
        }
    }

    #[test]
    fn azimuth_elevation_round_trips_and_is_oriented() {
        for (az, el) in [(0.0, 0.0), (30.0, 10.0), (-120.0, -45.0), (179.0, 89.0)] {
            let (a, e) = azimuth_elevation(direction_from(az, el));
            assert!((a - az).abs() < 1e-9 && (e - el).abs() < 1e-9);
        }
        // Right is positive azimuth, up positive elevation.
        assert!((azimuth_elevation([0.0, 1.0, 0.0]).0 - 90.0).abs() < 1e-12);
        assert!((azimuth_elevation([0.0, 0.0, 1.0]).1 - 90.0).abs() < 1e-12);
        // Directions a camera does not see have no position.
        let pin = cameras()[0];
        assert!(pin.image_position([-1.0, 0.0, 0.0]).is_none());
        let pano = cameras()[1];
        assert!(pano.image_position(direction_from(150.0, 0.0)).is_none());
        assert!(pano.image_position([0.0; 3]).is_none());
    }
}
