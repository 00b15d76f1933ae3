//! [`Shading`]: a prepared shader — [`crate::settings::ShadeSettings`] checked against one
//! data file, textures loaded once (`shading/prepare.rs`) — and the per-pixel rule that every
//! front end (CLI, sequences, viewer) uses, which this file holds.
//!
//! A hit pixel of object k is the product of its layers' colours (linear RGB):
//!
//! | layer | colour |
//! | --- | --- |
//! | texture | object k's first texture at the moved coordinates (u_tex, v_tex), lamps included |
//! | time, window | the window texture where t0 ≤ t_emit ≤ t0 + Δt, else the first texture (t_emit alone decides) |
//! | time, travel | false colour of the travel time −t_emit over [travel_min, travel_max] ([`crate::legend`]) |
//! | frequency | black body at g·T_k ([`crate::frequency_shader`]: normalized or physical Y(gT)/Y(T)·exposure), through the 1-D table in g·T ([`crate::gt_table`]) |
//! | light | ambient + Σ_k on_k·intensity_k·color_k·light_k (the data file's light planes) |
//!
//! With the light layer and no other layer, the albedo is the first texture. Without the light
//! layer, pixels painted by a texture (texture or time-window layer) get the preview's Lambert
//! factor 0.25 + 0.75·max(cos_i, 0), so the texture layer alone with the scene's textures is
//! exactly the render's preview; black bodies and false colours are not Lambert-shaded.
//! Pixels that hit nothing, failed, or were not traced take [`crate::texture_shader::status_colour`]'s colours.
//!
//! Pictures for display ([`Shading::image`]) scale each hit pixel by 2^`ev` and pass it
//! through the display tone curve ([`crate::colour::tone_map`]), then draw the reference
//! squares and composite the overlay layer ([`crate::layer`]: orientation marks (`grid`),
//! the travel-time legend, the squares' labels); [`Shading::linear`] gives the colours
//! before all of that (the EXR output). [`Shading::image_into_with`] gives the same bytes from
//! a [`Channels`] copy of the data file, made once per file: each sample is coloured by the
//! same rule ([`Shading::colour`] of a [`crate::channels::Sample`]), rows in three passes
//! (colours, tone curve over the row, 8-bit encoding).
//!
//! Caps, checked with the other settings so that every front end gets them: at most
//! [`crate::settings::MAX_LAMPS`] lamps per object and [`crate::settings::MAX_LIGHT_SOURCES`]
//! light sources (or the data file's
//! light count, if larger); image files as [`crate::texture`] caps them.
//!
//! Texture coordinates: u_tex = scale_u·u + offset_u − rotation_deg/360 (the body turned about
//! its axis: u is the longitude), v_tex = scale_v·v + offset_v. A lamp covers the disc of
//! angular radius `radius_deg` around its centre on the unit sphere (longitude 2π·u_tex,
//! latitude π(v_tex − ½)) and is on when ((t − phase)/period) mod 1 < duty, t being the
//! coordinate time of emission (observer time + t_emit); off it shows a tenth of its colour.

mod prepare;

use datafile::DataFile;
use image::{RgbImage, RgbaImage};
use rayon::prelude::*;

use crate::body::PreparedObject;
use crate::channels::{Channels, Needs, Sample};
use crate::colour::{display_srgb8, linear_to_srgb8_row, rgb_to_srgb8_fast, tone_map, TONE_KNEE};
use crate::frequency_shader::{blackbody_colour, reference_square, Brightness, REFERENCE_SQUARES};
use crate::gt_table::gt_table;
use crate::layer::{composite, Overlays};
use crate::legend::false_colour;
use crate::polarization::{draw_ticks, PolSample};
use crate::settings::TimeMode;
use crate::texture_shader::{displayed, shading_factor, status_colour_of, BACKGROUND, FAILED};

/// Settings checked against a data file, textures loaded: ready to shade it (or other data
/// files with the same objects and lights) any number of times.
#[derive(Clone, Debug)]
pub struct Shading {
    texture: bool,
    frequency: bool,
    time: bool,
    light: bool,
    objects: Vec<PreparedObject>,
    brightness: Brightness,
    time_mode: TimeMode,
    window: (f64, f64),
    travel: (f64, f64),
    legend: bool,
    reference_squares: bool,
    ambient: f32,
    /// on·intensity·color per light plane.
    lights: Vec<[f32; 3]>,
    observer_time: f64,
    /// 2^ev, applied before the display tone curve.
    gain: f32,
    /// The camera, for orientation marks (`grid`); `None` without them.
    marks: Option<scene::Camera>,
    /// The polarization layer, and each object's polarization axis (unit; `None`:
    /// unpolarized).
    polarization: bool,
    axes: Vec<Option<[f64; 3]>>,
}

/// Most exposure compensation, in stops either way.
pub const MAX_EV: f64 = 20.0;

impl Shading {
    /// Shades `data` into a new 8-bit sRGB image of its picture size (rows in parallel; the
    /// result does not depend on the thread count).
    pub fn image(&self, data: &DataFile) -> RgbImage {
        let mut bytes = Vec::new();
        self.image_into(data, &mut bytes);
        let (w, h) = data.picture_size();
        match (u32::try_from(w), u32::try_from(h)) {
            (Ok(w), Ok(h)) if !bytes.is_empty() => {
                RgbImage::from_raw(w, h, bytes).unwrap_or_else(|| RgbImage::new(0, 0))
            }
            _ => RgbImage::new(0, 0),
        }
    }

    /// Shades `data` into `bytes` (resized to the picture's width × height × 3, RGB8
    /// row-major, row 0 at the top), reusing the caller's buffer: the path of a data file
    /// shaded once (`godel shade`; the viewer shades a [`Channels`] copy with
    /// [`Shading::image_into_with`], which gives the same bytes). An
    /// anti-aliased file is shaded sample by sample and box-filtered
    /// ([`DataFile::box_filter`]). Overlays (reference squares, legend) included.
    pub fn image_into(&self, data: &DataFile, bytes: &mut Vec<u8>) {
        self.image_rows_into(data, bytes);
        let (w, h) = data.picture_size();
        let s = data.supersample().max(1);
        self.draw_ticks(w, h, bytes, &|col, row| {
            let r = data
                .records
                .get(data.width * (s * row + s / 2) + s * col + s / 2)?;
            Some(PolSample {
                object: if r.is_hit() { r.object } else { -1 },
                pol: r.pol,
                dir: r.dir,
            })
        });
        self.draw_overlays(w, h, bytes);
    }

    /// The polarization layer's ticks over the picture in `bytes` (w × h RGB8), each cell read
    /// at the sample `at(col, row)` of its centre pixel; nothing without the layer.
    fn draw_ticks(
        &self,
        w: usize,
        h: usize,
        bytes: &mut Vec<u8>,
        at: &dyn Fn(usize, usize) -> Option<PolSample>,
    ) {
        if !self.polarization || bytes.len() != w * h * 3 {
            return;
        }
        let (Ok(wu), Ok(hu)) = (u32::try_from(w), u32::try_from(h)) else {
            return;
        };
        // The picture's buffer itself, not a copy (given back below).
        if let Some(mut img) = RgbImage::from_raw(wu, hu, std::mem::take(bytes)) {
            draw_ticks(&mut img, at, &self.axes);
            *bytes = img.into_raw();
        }
    }

    /// [`Shading::image_into`] without the reference squares and the overlay layer: for a
    /// picture shaded in bands of rows, each band a data file of its own (pixels are shaded
    /// one by one), over which [`Shading::draw_overlays`] then draws them once.
    pub fn image_rows_into(&self, data: &DataFile, bytes: &mut Vec<u8>) {
        let (w, h) = data.picture_size();
        bytes.clear();
        if w == 0 || h == 0 || data.records.len() < data.width * data.height {
            return;
        }
        bytes.resize(w * h * 3, 0);
        bytes
            .par_chunks_mut(w * 3)
            .enumerate()
            .for_each(|(row, out)| {
                for (col, px) in out.chunks_exact_mut(3).enumerate() {
                    // Each sample as displayed (hit samples through exposure and the tone
                    // curve; status colours are display codes), then the pixel's box filter.
                    let c = data.box_filter(col, row, |i| self.displayed(data, i));
                    px.copy_from_slice(&rgb_to_srgb8_fast(c));
                }
            });
    }

    /// Shades `data` into linear, scene-referred RGB (row-major, row 0 at the top) at the
    /// picture size, each pixel the box filter of its samples: no exposure compensation, no
    /// tone curve, no overlays; what `godel shade -o x.exr` writes.
    pub fn linear(&self, data: &DataFile) -> Vec<[f32; 3]> {
        let (w, h) = data.picture_size();
        if data.records.len() < data.width * data.height {
            return Vec::new();
        }
        (0..w * h)
            .into_par_iter()
            .map(|p| data.box_filter(p % w, p / w, |i| self.pixel(data, i)))
            .collect()
    }

    /// Sample `i` as displayed, in linear light before the 8-bit encoding: hit samples
    /// scaled by the exposure gain and put through the tone curve, status colours as they are.
    fn displayed(&self, data: &DataFile, i: usize) -> [f32; 3] {
        let c = self.pixel(data, i);
        match data.records.get(i) {
            Some(r) => displayed(c, r, self.gain),
            None => c,
        }
    }

    /// Linear RGB of record `i` (row-major index) of `data`: one sample of an anti-aliased
    /// file.
    pub fn pixel(&self, data: &DataFile, i: usize) -> [f32; 3] {
        let Some(rec) = data.records.get(i) else {
            return FAILED;
        };
        let light = |k: usize| {
            data.lights
                .get(k)
                .and_then(|p| p.get(i))
                .copied()
                .unwrap_or(0.0)
        };
        self.colour(&Sample::of(rec), light)
    }

    /// The channels these settings read: what [`Channels::new`] must copy for
    /// [`Shading::image_into_with`].
    pub fn needs(&self) -> Needs {
        let paints = self.texture || self.time || self.light;
        Needs {
            texture_coordinates: paints,
            shift: self.frequency,
            incidence: !self.light && (self.texture || self.time),
            lights: self.light,
            polarization: self.polarization,
        }
    }

    /// [`Shading::image`] from the channels of a data file ([`Channels`], made once per file):
    /// the same picture, byte for byte; an empty image if `channels` lacks a channel these
    /// settings read.
    pub fn image_with(&self, channels: &Channels) -> RgbImage {
        let mut bytes = Vec::new();
        self.image_into_with(channels, &mut bytes);
        let (w, h) = channels.picture_size();
        match (u32::try_from(w), u32::try_from(h)) {
            (Ok(w), Ok(h)) if !bytes.is_empty() => {
                RgbImage::from_raw(w, h, bytes).unwrap_or_else(|| RgbImage::new(0, 0))
            }
            _ => RgbImage::new(0, 0),
        }
    }

    /// [`Shading::image_into`] from the channels of a data file: the same bytes. `bytes` is
    /// left empty if `channels` lacks a channel these settings read ([`Shading::needs`]).
    /// Rows in parallel, each in three passes: linear colours of the row, the exposure and
    /// tone curve over the whole row, the 8-bit encoding.
    pub fn image_into_with(&self, channels: &Channels, bytes: &mut Vec<u8>) {
        let (w, h) = channels.picture_size();
        bytes.clear();
        if w == 0 || h == 0 || !channels.serves(self.needs(), self.lights.len()) {
            return;
        }
        let s = channels.supersample.max(1);
        bytes.resize(w * h * 3, 0);
        bytes.par_chunks_mut(w * 3).enumerate().for_each_init(
            || (vec![0.0f32; w * 3], vec![false; w * 3]),
            |(row_rgb, hit), (row, out)| {
                if s == 1 {
                    self.row_linear(channels, row * channels.width, row_rgb, hit);
                    tone_row(row_rgb, hit, self.gain);
                } else {
                    for (col, px) in row_rgb.chunks_exact_mut(3).enumerate() {
                        px.copy_from_slice(&self.box_displayed(channels, col, row, s));
                    }
                }
                linear_to_srgb8_row(row_rgb, out);
            },
        );
        self.draw_ticks(w, h, bytes, &|col, row| {
            let i = channels.width * (s * row + s / 2) + s * col + s / 2;
            let p = channels.polarization(i);
            let hit = channels.sample(i).status == datafile::RayStatus::Hit;
            Some(PolSample {
                object: if hit { p.object } else { -1 },
                ..p
            })
        });
        self.draw_overlays(w, h, bytes);
    }

    /// Linear colours of the samples from `start` on into `rgb` (3 values per sample),
    /// `hit` telling which values get the exposure and tone curve.
    fn row_linear(&self, channels: &Channels, start: usize, rgb: &mut [f32], hit: &mut [bool]) {
        let pixels = rgb.chunks_exact_mut(3).zip(hit.chunks_exact_mut(3));
        for (k, (px, hit)) in pixels.enumerate() {
            let i = start + k;
            let sample = channels.sample(i);
            let c = self.colour(&sample, |l| channels.light(l, i));
            hit.fill(tone_mapped(&sample, c));
            px.copy_from_slice(&c);
        }
    }

    /// Picture pixel (`col`, `row`) of an anti-aliased file as displayed: each sample as
    /// displayed, then the box filter (as [`DataFile::box_filter`]).
    fn box_displayed(&self, channels: &Channels, col: usize, row: usize, s: usize) -> [f32; 3] {
        let mut sum = [0.0f64; 3];
        for j in 0..s {
            for k in 0..s {
                let i = (s * row + j) * channels.width + s * col + k;
                let sample = channels.sample(i);
                let c = self.colour(&sample, |l| channels.light(l, i));
                let c = if tone_mapped(&sample, c) {
                    c.map(|x| tone_map(x * self.gain))
                } else {
                    c
                };
                for (a, b) in sum.iter_mut().zip(c) {
                    *a += f64::from(b);
                }
            }
        }
        let n = (s * s) as f64;
        sum.map(|v| (v / n) as f32)
    }

    /// Linear RGB of one sample (see the module documentation), `light(k)` giving its value
    /// of light plane k: the rule both the record path and the channel path use.
    #[inline]
    pub fn colour(&self, s: &Sample, light: impl Fn(usize) -> f32) -> [f32; 3] {
        if let Some(c) = status_colour_of(s.status, s.object, BACKGROUND) {
            return c;
        }
        let Some(obj) = self.objects.get(s.object as usize) else {
            return FAILED;
        };
        let uv = [s.u, s.v];
        let t_emit = f64::from(s.t_emit);
        let t = self.observer_time + t_emit;
        let mut c = [1.0f32; 3];
        let mut painted = false;
        let mut coloured = false;
        if self.texture {
            c = mul(c, obj.sample(&obj.first, uv, t));
            painted = true;
        }
        if self.time {
            match self.time_mode {
                TimeMode::Window => {
                    let inside = t_emit >= self.window.0 && t_emit <= self.window.1;
                    let tex = if inside { &obj.second } else { &obj.first };
                    c = mul(c, obj.sample(tex, uv, t));
                    painted = true;
                }
                TimeMode::Travel => {
                    let (lo, hi) = self.travel;
                    c = mul(c, false_colour((-t_emit - lo) / (hi - lo)));
                    coloured = true;
                }
            }
        }
        if self.frequency {
            match self.blackbody(f64::from(s.g), obj) {
                Some(b) => c = mul(c, b),
                None => return FAILED,
            }
            coloured = true;
        }
        if self.light {
            if !painted && !coloured {
                c = obj.sample(&obj.first, uv, t);
            }
            let mut l = [self.ambient; 3];
            for (k, w) in self.lights.iter().enumerate() {
                let x = light(k);
                let x = if x.is_finite() { x.max(0.0) } else { 0.0 };
                for (lc, wc) in l.iter_mut().zip(w) {
                    *lc += wc * x;
                }
            }
            c = mul(c, l);
        } else if painted {
            let f = shading_factor(s.cos_i);
            c = c.map(|v| v * f);
        }
        c
    }

    /// Linear sRGB of object `obj`'s black body seen with shift `g`; `None` for g not finite
    /// and positive.
    fn blackbody(&self, g: f64, obj: &PreparedObject) -> Option<[f32; 3]> {
        if !(g.is_finite() && g > 0.0) {
            return None;
        }
        let gt = g * obj.temperature;
        let Some(e) = gt_table().get(gt) else {
            return blackbody_colour(g, obj.temperature, self.brightness);
        };
        Some(match self.brightness {
            Brightness::Normalized => e.normalized,
            Brightness::Physical { exposure } => {
                let scale = (exposure * e.luminance / obj.luminance) as f32;
                let rgb = e.unit.map(|c| c * scale);
                let max = rgb[0].max(rgb[1]).max(rgb[2]);
                if max > 1.0 {
                    rgb.map(|c| c / max)
                } else {
                    rgb
                }
            }
        })
    }

    /// What the overlay layer ([`crate::layer`]) shows with these settings: orientation
    /// marks (`grid`), the travel-time legend, the reference squares' labels.
    pub fn overlays_shown(&self) -> Overlays {
        let legend = self.time && self.time_mode == TimeMode::Travel && self.legend;
        let squares = self.frequency && self.reference_squares;
        Overlays {
            marks: self.marks,
            legend: legend.then_some(self.travel),
            polarization: self.polarization && self.axes.iter().any(Option::is_some),
            reference_labels: if squares {
                self.objects.iter().map(|o| o.temperature).collect()
            } else {
                Vec::new()
            },
        }
    }

    /// The overlay layer of a `w` × `h` picture (`None`: nothing to draw); what the viewer
    /// serves for the page to composite over its own shading.
    pub fn overlay(&self, w: u32, h: u32) -> Option<RgbaImage> {
        self.overlays_shown().draw(w, h)
    }

    /// Orientation marks for `camera` instead of the data file's (a view looked at from a
    /// full-sphere file); nothing changes without `grid`.
    pub fn mark_camera(&mut self, camera: &scene::Camera) {
        if self.marks.is_some() {
            self.marks = Some(*camera);
        }
    }

    /// The reference squares (frequency layer), drawn into the `w` × `h` RGB8 picture
    /// `bytes`, then the overlay layer composited over it.
    pub fn draw_overlays(&self, w: usize, h: usize, bytes: &mut Vec<u8>) {
        let squares = self.frequency && self.reference_squares;
        let shown = self.overlays_shown();
        if shown.is_empty() {
            return;
        }
        let (Ok(wu), Ok(hu)) = (u32::try_from(w), u32::try_from(h)) else {
            return;
        };
        if bytes.len() != w * h * 3 {
            return;
        }
        // The picture's buffer itself, not a copy (given back below).
        let Some(mut img) = RgbImage::from_raw(wu, hu, std::mem::take(bytes)) else {
            return;
        };
        if squares {
            let shown = self.objects.iter().take(REFERENCE_SQUARES).enumerate();
            for (k, obj) in shown {
                let Some((x0, y0, side)) = reference_square(k, w, h) else {
                    continue;
                };
                // The colour a pixel at g = 1 shows: through exposure and the tone curve.
                let c = blackbody_colour(1.0, obj.temperature, self.brightness).unwrap_or(FAILED);
                let c = display_srgb8(c, self.gain);
                for y in y0..y0 + side {
                    for x in x0..x0 + side {
                        img.put_pixel(x as u32, y as u32, image::Rgb(c));
                    }
                }
            }
        }
        if let Some(layer) = shown.draw(wu, hu) {
            composite(&mut img, &layer);
        }
        *bytes = img.into_raw();
    }
}

fn mul(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}

/// Whether a sample's colour `c` goes through the exposure and tone curve (as
/// [`displayed`]: hit samples not coloured as failed).
#[inline]
fn tone_mapped(s: &Sample, c: [f32; 3]) -> bool {
    status_colour_of(s.status, s.object, BACKGROUND).is_none() && c != FAILED
}

/// [`tone_map`] of `x·gain` for every value of the row that is `hit`, the others
/// unchanged; written without branches on the values so that the loop vectorises, and equal
/// to [`tone_map`] bit for bit (the same operations in the same order, then a choice).
fn tone_row(rgb: &mut [f32], hit: &[bool], gain: f32) {
    for (x, &hit) in rgb.iter_mut().zip(hit) {
        let g = *x * gain;
        let y = (g - TONE_KNEE) / (1.0 - TONE_KNEE);
        let shoulder = TONE_KNEE + (1.0 - TONE_KNEE) * (y / (1.0 + y));
        let mut t = if g <= TONE_KNEE { g } else { shoulder };
        t = if g == f32::INFINITY { 1.0 } else { t };
        t = if g.is_nan() { 0.0 } else { t };
        *x = if hit { t } else { *x };
    }
}
