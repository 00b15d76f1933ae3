//! Reading the full sphere at a direction (docs/physics.md, "Reading the sphere, and its
//! error"): [`Filter::Nearest`] takes the record of the sphere pixel the direction falls in;
//! [`Filter::Smooth`] interpolates bilinearly between the four sphere pixels around it where
//! all four show the same image of one object, and takes the nearest elsewhere (at the edges
//! of objects and images, and next to the poles).
//!
//! Four pixels show one image when all are hits of the same object and their emission times
//! lie within [`SAME_IMAGE_DT`] and their body coordinates u (around the body, so taken across
//! the seam u = 0 = 1) and v within [`SAME_IMAGE_DUV`] of one another: within an image,
//! neighbouring pixels of a 720×360 sphere differ in t_emit by at most 0.1, while two images
//! of one object that touch are emitted a loop of the light ray apart (2.86a in the views of
//! docs/physics.md), so an image boundary is never taken for an image.
//!
//! Interpolated records are the weighted means of the four records, field by field (u on the
//! circle, the photon direction renormalized, the polarization made orthogonal to it again
//! and renormalized), so their fields still belong together to first
//! order in the pixel size; `object` and `status` are the four's common values. Light planes
//! are interpolated with the same weights where all four values are finite.

use datafile::PixelRecord;

/// How a direction's record is read from the sphere.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// The record of the sphere pixel the direction falls in.
    Nearest,
    /// Bilinear within one image of one object, nearest elsewhere.
    #[default]
    Smooth,
}

/// Most emission-time spread (coordinate time, units of a) of four sphere pixels taken as
/// one image.
pub const SAME_IMAGE_DT: f64 = 0.5;
/// Most spread of four sphere pixels' body coordinates u (on the circle) and v taken as one
/// image.
pub const SAME_IMAGE_DUV: f64 = 0.25;

/// The sphere pixels a direction's record is made of, with their weights (summing to 1):
/// one for the nearest, four for a bilinear blend.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Taps {
    pub taps: [(usize, f64); 4],
    pub count: usize,
}

impl Taps {
    fn one(i: usize) -> Taps {
        Taps {
            taps: [(i, 1.0), (i, 0.0), (i, 0.0), (i, 0.0)],
            count: 1,
        }
    }

    /// The taps in use.
    pub fn used(&self) -> &[(usize, f64)] {
        &self.taps[..self.count]
    }
}

/// Index of the pixel containing position `p` of a `width` × `height` sphere (positions as
/// `SphereSource::position`: pixel (c, r) covers [c, c + 1) × [r, r + 1)); columns wrap,
/// rows are clamped at the poles.
pub fn nearest_index(width: usize, height: usize, p: [f64; 2]) -> usize {
    let (w, h) = (width as i64, height as i64);
    let col = (p[0].floor() as i64).rem_euclid(w);
    let row = (p[1].floor() as i64).clamp(0, h - 1);
    (row * w + col) as usize
}

/// The taps for position `p` of the sphere `records` (`width` × `height`, row-major).
pub fn taps(
    records: &[PixelRecord],
    width: usize,
    height: usize,
    p: [f64; 2],
    filter: Filter,
) -> Taps {
    let nearest = Taps::one(nearest_index(width, height, p));
    if filter == Filter::Nearest {
        return nearest;
    }
    // The four pixel centres around p (centres at half-integers); none across a pole.
    let (x, y) = (p[0] - 0.5, p[1] - 0.5);
    let (c0, r0) = (x.floor(), y.floor());
    if r0 < 0.0 || r0 + 1.0 > height as f64 - 1.0 || !(x.is_finite() && y.is_finite()) {
        return nearest;
    }
    // Weights within a hair of 0 or 1 are exactly that, so a direction at a pixel centre
    // reads that pixel's record unchanged.
    let snap = |f: f64| {
        if f < 1e-9 {
            0.0
        } else if f > 1.0 - 1e-9 {
            1.0
        } else {
            f
        }
    };
    let (fx, fy) = (snap(x - c0), snap(y - r0));
    let w = width as i64;
    let index = |dc: i64, dr: i64| {
        let col = (c0 as i64 + dc).rem_euclid(w);
        (r0 as usize + dr as usize) * width + col as usize
    };
    let taps = [
        (index(0, 0), (1.0 - fx) * (1.0 - fy)),
        (index(1, 0), fx * (1.0 - fy)),
        (index(0, 1), (1.0 - fx) * fy),
        (index(1, 1), fx * fy),
    ];
    if one_image(taps.map(|(i, _)| &records[i])) {
        Taps { taps, count: 4 }
    } else {
        nearest
    }
}

/// Whether four records show the same image of one object (see the module doc).
fn one_image(r: [&PixelRecord; 4]) -> bool {
    let first = r[0];
    if !r.iter().all(|x| x.is_hit() && x.object == first.object) {
        return false;
    }
    let spread = |f: &dyn Fn(&PixelRecord) -> f64| {
        let values = r.map(f);
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        hi - lo
    };
    let u0 = f64::from(first.u);
    spread(&|x| f64::from(x.t_emit)) <= SAME_IMAGE_DT
        && spread(&|x| unwrapped(f64::from(x.u), u0)) <= SAME_IMAGE_DUV
        && spread(&|x| f64::from(x.v)) <= SAME_IMAGE_DUV
}

/// `u` moved by a whole turn to lie within half a turn of `near`.
fn unwrapped(u: f64, near: f64) -> f64 {
    u - (u - near).round()
}

/// The record the taps make: the single tap's record, or the weighted mean of four.
pub fn record(records: &[PixelRecord], t: &Taps) -> PixelRecord {
    // One tap, or a blend that is one of its taps (a direction at a pixel centre).
    if let Some(&(i, _)) = t.used().iter().find(|&&(_, w)| w == 1.0) {
        return records[i];
    }
    let (first, _) = t.taps[0];
    let mut out = records[first];
    let mean = |f: &dyn Fn(&PixelRecord) -> f64| -> f32 {
        t.used()
            .iter()
            .map(|&(i, w)| w * f(&records[i]))
            .sum::<f64>() as f32
    };
    let u0 = f64::from(out.u);
    let u = f64::from(mean(&|r| unwrapped(f64::from(r.u), u0)));
    out.u = (u - u.floor()) as f32;
    out.v = mean(&|r| f64::from(r.v));
    out.g = mean(&|r| f64::from(r.g));
    out.t_emit = mean(&|r| f64::from(r.t_emit));
    out.x = mean(&|r| f64::from(r.x));
    out.y = mean(&|r| f64::from(r.y));
    out.z = mean(&|r| f64::from(r.z));
    out.lambda = mean(&|r| f64::from(r.lambda));
    out.cos_i = mean(&|r| f64::from(r.cos_i));
    let dir = [0, 1, 2].map(|k| f64::from(mean(&|r| f64::from(r.dir[k]))));
    let n = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    if n > 0.0 {
        out.dir = dir.map(|c| (c / n) as f32);
    }
    // The polarization channels: the mean made orthogonal to the mean direction again and
    // renormalized (all zero in files without them, and left so).
    let pol = [0, 1, 2].map(|k| f64::from(mean(&|r| f64::from(r.pol[k]))));
    let d = out.dir.map(f64::from);
    let along = pol[0] * d[0] + pol[1] * d[1] + pol[2] * d[2];
    let pol = [0, 1, 2].map(|k| pol[k] - along * d[k]);
    let m = (pol[0] * pol[0] + pol[1] * pol[1] + pol[2] * pol[2]).sqrt();
    if m > 0.0 {
        out.pol = pol.map(|c| (c / m) as f32);
    }
    out
}

/// A light plane's value at the taps: their weighted mean where all are finite, else the
/// heaviest tap's value (NaN marks an occlusion search that ran out of work).
pub fn light(plane: &[f32], t: &Taps) -> f32 {
    let used = t.used();
    if used.iter().all(|&(i, _)| plane[i].is_finite()) {
        used.iter()
            .map(|&(i, w)| w * f64::from(plane[i]))
            .sum::<f64>() as f32
    } else {
        let heaviest = used
            .iter()
            .fold(used[0], |a, &b| if b.1 > a.1 { b } else { a });
        plane[heaviest.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use datafile::RayStatus;

    /// A 4×4 sphere of one object with fields linear in the pixel position.
    fn linear_sphere() -> Vec<PixelRecord> {
        (0..16)
            .map(|i| {
                let (c, r) = ((i % 4) as f32, (i / 4) as f32);
                let mut rec = PixelRecord::miss(RayStatus::Hit);
                rec.object = 0;
                rec.u = 0.05 * c;
                rec.v = 0.05 * r;
                rec.t_emit = -1.0 - 0.1 * c - 0.01 * r;
                rec.g = 1.0 + 0.02 * c;
                rec.dir = [1.0, 0.0, 0.0];
                rec
            })
            .collect()
    }

    #[test]
    fn inside_one_image_the_blend_is_bilinear() {
        let s = linear_sphere();
        // Between the centres of (1, 1), (2, 1), (1, 2), (2, 2), a quarter of the way.
        let p = [1.5 + 0.25, 1.5 + 0.75];
        let t = taps(&s, 4, 4, p, Filter::Smooth);
        assert_eq!(t.count, 4);
        let r = record(&s, &t);
        assert!((r.u - 0.05 * 1.25).abs() < 1e-6 && (r.v - 0.05 * 1.75).abs() < 1e-6);
        assert!((r.t_emit - (-1.0 - 0.125 - 0.0175)).abs() < 1e-6);
        assert!((r.g - 1.025).abs() < 1e-6);
        // Nearest: the pixel containing p, unchanged.
        let n = taps(&s, 4, 4, p, Filter::Nearest);
        assert_eq!(n.used(), &[(2 * 4 + 1, 1.0)]);
        // At a pixel centre the smooth record is that pixel's, bit for bit.
        let at = taps(&s, 4, 4, [2.5, 1.5], Filter::Smooth);
        assert_eq!(record(&s, &at), s[4 + 2]);
    }

    #[test]
    fn edges_images_and_poles_take_the_nearest() {
        let p = [1.9, 1.9];
        let nearest = nearest_index(4, 4, p);
        // Another object among the four.
        let mut s = linear_sphere();
        s[4 + 2].object = 1;
        assert_eq!(taps(&s, 4, 4, p, Filter::Smooth).count, 1);
        // A miss among the four.
        let mut s = linear_sphere();
        s[2 * 4 + 2] = PixelRecord::miss(RayStatus::Escaped);
        assert_eq!(taps(&s, 4, 4, p, Filter::Smooth).count, 1);
        // Another image: emitted a loop earlier.
        let mut s = linear_sphere();
        s[2 * 4 + 2].t_emit -= 2.6;
        let t = taps(&s, 4, 4, p, Filter::Smooth);
        assert_eq!(t.used(), &[(nearest, 1.0)]);
        // Another part of the body at the same time.
        let mut s = linear_sphere();
        s[2 * 4 + 2].v += 0.5;
        assert_eq!(taps(&s, 4, 4, p, Filter::Smooth).count, 1);
        // Next to a pole the rows would cross it.
        let s = linear_sphere();
        assert_eq!(taps(&s, 4, 4, [1.9, 0.2], Filter::Smooth).count, 1);
        assert_eq!(taps(&s, 4, 4, [1.9, 3.7], Filter::Smooth).count, 1);
    }

    #[test]
    fn u_is_blended_across_the_seam_and_columns_wrap() {
        let mut s = linear_sphere();
        // Columns 3 and 0 are neighbours across the sphere's seam; u runs 0.98, 0.02 there.
        for r in 0..4 {
            s[r * 4 + 3].u = 0.98;
            s[r * 4].u = 0.02;
        }
        let t = taps(&s, 4, 4, [4.0, 2.0], Filter::Smooth);
        assert_eq!(t.count, 4);
        assert!(t.used().iter().any(|&(i, _)| i % 4 == 0));
        let u = record(&s, &t).u;
        assert!(!(0.005..=0.995).contains(&u), "u {u}");
        // Light planes: the weighted mean, or the heaviest tap where one is NaN.
        let plane: Vec<f32> = (0..16).map(|i| i as f32).collect();
        let t = taps(&linear_sphere(), 4, 4, [1.75, 1.5], Filter::Smooth);
        assert!((light(&plane, &t) - 5.25).abs() < 1e-6);
        let mut holes = plane.clone();
        holes[6] = f32::NAN;
        assert_eq!(light(&holes, &t), 5.0);
    }
}
