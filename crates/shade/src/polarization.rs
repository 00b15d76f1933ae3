//! The polarization layer (docs/physics.md, "Polarization"): short line segments ("ticks") on
//! a regular grid over the picture, each along the polarization direction the observer sees
//! at its pixel, as in sky polarization maps, coloured by that angle on a cyclic colour map
//! (its legend is drawn by the overlay layer, [`crate::layer`]).
//!
//! At a pixel that shows an object whose light is polarized along the body axis e (the
//! scene's `polarization = { axis = … }`, or the settings' `objects.NAME.polarization`), the
//! observed angle from screen-up towards screen-right is χ =
//! atan2(ê·(pol × dir), ê·pol) ([`spacetime::polarization::observed_angle`]), read from the
//! data file's `pol_*` and `dir_*` channels: no re-trace. On the picture screen-up is up and
//! screen-right is right, so the tick runs along (sin χ, −cos χ) in image coordinates (y
//! down). χ and χ + π are one line: the colour map has period π (hue 2χ).

use image::RgbImage;
use spacetime::polarization::observed_angle;

/// What the layer reads of one sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolSample {
    /// The object hit (−1: none).
    pub object: i32,
    pub pol: [f32; 3],
    pub dir: [f32; 3],
}

/// The grid's spacing in pixels on a `w` × `h` picture: 16 ticks across the shorter side,
/// never closer than 12 pixels.
pub fn tick_spacing(w: usize, h: usize) -> usize {
    (w.min(h) / 16).max(12)
}

/// The observed angle χ (radians, in [0, π)) of the sample's light, or `None` where it shows
/// no polarized object (nothing hit, an unpolarized object, light along the axis).
pub fn angle(s: &PolSample, axes: &[Option<[f64; 3]>]) -> Option<f64> {
    let axis = (*axes.get(usize::try_from(s.object).ok()?)?)?;
    let (pol, dir) = (s.pol.map(f64::from), s.dir.map(f64::from));
    let chi = observed_angle(pol, dir, axis)?;
    Some(chi.rem_euclid(std::f64::consts::PI))
}

/// 8-bit sRGB of the cyclic colour map at the angle `chi` (period π): the hue circle at
/// 2χ (red at 0, green-yellow at 60°, cyan at 90°, blue at 120°), saturated and bright.
pub fn cyclic_colour(chi: f64) -> [u8; 3] {
    let h = (2.0 * chi).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU * 6.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    let (r, g, b) = match h as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    // Saturation 0.85: a little white in every colour keeps the ticks light on dark skies.
    [r, g, b].map(|c: f64| ((0.15 + 0.85 * c) * 255.0).round() as u8)
}

/// The ticks' outline: dark, so that ticks stay visible on any colour.
const OUTLINE: [u8; 3] = [20, 20, 20];

/// Draws the ticks over `img`: at the centre of each cell of the grid ([`tick_spacing`]) whose
/// sample `at(col, row)` shows a polarized object ([`angle`]), a segment of 0.8 spacings
/// along the observed direction, with a dark outline. Returns the number of ticks drawn.
pub fn draw_ticks(
    img: &mut RgbImage,
    at: &dyn Fn(usize, usize) -> Option<PolSample>,
    axes: &[Option<[f64; 3]>],
) -> usize {
    let (w, h) = (img.width() as usize, img.height() as usize);
    if w == 0 || h == 0 || axes.iter().all(Option::is_none) {
        return 0;
    }
    let step = tick_spacing(w, h);
    let half = 0.4 * step as f64;
    let mut drawn = 0;
    for cy in (step / 2..h).step_by(step) {
        for cx in (step / 2..w).step_by(step) {
            let Some(chi) = at(cx, cy).and_then(|s| angle(&s, axes)) else {
                continue;
            };
            let (dx, dy) = (chi.sin(), -chi.cos());
            let colour = cyclic_colour(chi);
            // The outline 3 pixels wide (5 on grids of 14 pixels and more), the colour over it.
            let core = if step >= 14 { 1 } else { 0 };
            for (radius, c) in [(core + 1, OUTLINE), (core, colour)] {
                let n = (2.0 * half * 2.0).ceil() as i64;
                for i in 0..=n {
                    let t = -half + 2.0 * half * i as f64 / n as f64;
                    let (x, y) = (cx as f64 + t * dx, cy as f64 + t * dy);
                    plot(img, x.round() as i64, y.round() as i64, radius, c);
                }
            }
            drawn += 1;
        }
    }
    drawn
}

/// Fills the square of half-width `radius` around (x, y), clipped to the image.
fn plot(img: &mut RgbImage, x: i64, y: i64, radius: i64, c: [u8; 3]) {
    let (w, h) = (i64::from(img.width()), i64::from(img.height()));
    for yy in (y - radius).max(0)..=(y + radius).min(h - 1) {
        for xx in (x - radius).max(0)..=(x + radius).min(w - 1) {
            img.put_pixel(xx as u32, yy as u32, image::Rgb(c));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn the_colour_map_is_cyclic_with_period_pi() {
        for chi in [0.0, 0.3, 1.0, 2.5] {
            assert_eq!(cyclic_colour(chi), cyclic_colour(chi + PI));
        }
        assert_eq!(cyclic_colour(0.0), [255, 38, 38]);
        // A quarter turn is the opposite hue.
        assert_eq!(cyclic_colour(FRAC_PI_2), [38, 255, 255]);
        // Nearby angles, nearby colours (no jump at π).
        let d = |a: [u8; 3], b: [u8; 3]| (0..3).map(|i| a[i].abs_diff(b[i])).max().unwrap();
        assert!(d(cyclic_colour(PI - 1e-3), cyclic_colour(0.0)) <= 2);
    }

    #[test]
    fn ticks_run_along_the_observed_direction() {
        // A photon along x at the emitter, pol = z: the screen-up arrives as z, and
        // screen-right as pol × dir = y. Axis y: a quarter turn, a horizontal tick.
        let s = PolSample {
            object: 0,
            pol: [0.0, 0.0, 1.0],
            dir: [1.0, 0.0, 0.0],
        };
        let axes = [Some([0.0, 1.0, 0.0])];
        assert!((angle(&s, &axes).unwrap() - FRAC_PI_2).abs() < 1e-12);
        let mut img = RgbImage::new(60, 60);
        assert_eq!(draw_ticks(&mut img, &|_, _| Some(s), &axes), 25);
        // The tick at the cell centre (6, 6) of spacing 12: horizontal, cyan core.
        let colour = cyclic_colour(FRAC_PI_2);
        assert_eq!(img.get_pixel(9, 6).0, colour);
        assert_eq!(img.get_pixel(6, 9).0, [0, 0, 0], "nothing above or below");
        // Unpolarized, or nothing hit: no ticks.
        let mut img = RgbImage::new(60, 60);
        assert_eq!(draw_ticks(&mut img, &|_, _| Some(s), &[None]), 0);
        let miss = PolSample { object: -1, ..s };
        assert_eq!(draw_ticks(&mut img, &|_, _| Some(miss), &axes), 0);
        assert!(img.pixels().all(|p| p.0 == [0, 0, 0]));
        // Axis z: along screen-up, a vertical tick.
        let mut img = RgbImage::new(60, 60);
        draw_ticks(&mut img, &|_, _| Some(s), &[Some([0.0, 0.0, 2.0])]);
        assert_eq!(img.get_pixel(6, 9).0, cyclic_colour(0.0));
        assert_eq!(img.get_pixel(9, 6).0, [0, 0, 0]);
    }
}
