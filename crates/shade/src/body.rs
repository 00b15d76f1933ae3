//! One object's runtime shading data: its textures, the texture-coordinate map (offset,
//! scale, turn about the body axis) and its blinking lamps; the rule is in
//! [`crate::shading`]'s documentation.

use crate::checks::{colour, finite, invalid, positive};
use crate::error::ShadeError;
use crate::settings::Lamp;
use crate::texture::Texture;

/// Brightness of an off lamp relative to on.
const LAMP_OFF: f32 = 0.1;

/// A lamp ready to test pixels against.
#[derive(Clone, Debug)]
pub(crate) struct PreparedLamp {
    sin_lat: f64,
    cos_lat: f64,
    lon: f64,
    cos_radius: f64,
    period: f64,
    phase: f64,
    duty: f64,
    on: [f32; 3],
    off: [f32; 3],
}

/// One object's runtime shading data.
#[derive(Clone, Debug)]
pub(crate) struct PreparedObject {
    pub(crate) first: Texture,
    pub(crate) second: Texture,
    pub(crate) scale: [f64; 2],
    pub(crate) offset: [f64; 2],
    pub(crate) temperature: f64,
    /// Y(T) of the unshifted black body, for physical brightness.
    pub(crate) luminance: f64,
    pub(crate) lamps: Vec<PreparedLamp>,
}

impl PreparedObject {
    /// Texture `tex` (or a lamp) at the sample's moved texture coordinates (from body
    /// coordinates `uv`), emission time `t`.
    pub(crate) fn sample(&self, tex: &Texture, uv: [f32; 2], t: f64) -> [f32; 3] {
        let u = self.scale[0] * f64::from(uv[0]) + self.offset[0];
        let v = self.scale[1] * f64::from(uv[1]) + self.offset[1];
        if !self.lamps.is_empty() {
            let lon = std::f64::consts::TAU * u;
            let lat = std::f64::consts::PI * (v.clamp(0.0, 1.0) - 0.5);
            let (sin_lat, cos_lat) = lat.sin_cos();
            for lamp in &self.lamps {
                let cos_d =
                    sin_lat * lamp.sin_lat + cos_lat * lamp.cos_lat * (lon - lamp.lon).cos();
                if cos_d >= lamp.cos_radius {
                    let on = ((t - lamp.phase) / lamp.period).rem_euclid(1.0) < lamp.duty;
                    return if on { lamp.on } else { lamp.off };
                }
            }
        }
        tex.sample(u, v)
    }
}

pub(crate) fn prepare_lamp(field: &str, l: &Lamp) -> Result<PreparedLamp, ShadeError> {
    let u = finite(&format!("{field}.u"), l.u)?;
    let v = finite(&format!("{field}.v"), l.v)?;
    let radius = positive(&format!("{field}.radius_deg"), l.radius_deg)?;
    let period = positive(&format!("{field}.period"), l.period)?;
    let phase = finite(&format!("{field}.phase"), l.phase)?;
    let duty = l.duty;
    if !(0.0..=1.0).contains(&duty) {
        return Err(invalid(
            format!("{field}.duty"),
            format!("must be in [0, 1], got {duty}"),
        ));
    }
    let on = colour(&format!("{field}.color"), l.color)?;
    let lat = std::f64::consts::PI * (v.clamp(0.0, 1.0) - 0.5);
    Ok(PreparedLamp {
        sin_lat: lat.sin(),
        cos_lat: lat.cos(),
        lon: std::f64::consts::TAU * u,
        cos_radius: radius.min(180.0).to_radians().cos(),
        period,
        phase,
        duty,
        on,
        off: on.map(|c| c * LAMP_OFF),
    })
}
