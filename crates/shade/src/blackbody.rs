//! Black-body colour science for the frequency shader: the colour and brightness of a black
//! body at temperature T, and a lookup table in T so that a shader never integrates a
//! spectrum per pixel.
//!
//! Equations implemented:
//!
//! - Planck's law (SI units, exact 2019 SI constants h, c, k_B), per wavelength and per
//!   frequency:
//!   `B_λ(λ, T) = 2hc²/λ⁵ · 1/(exp(hc/(λ k_B T)) − 1)` in W·sr⁻¹·m⁻³, and
//!   `B_ν(ν, T) = 2hν³/c² · 1/(exp(hν/(k_B T)) − 1)` in W·sr⁻¹·m⁻²·Hz⁻¹.
//! - CIE 1931 2° standard observer: `X = Σ B_λ(λᵢ, T) x̄(λᵢ) Δλ` (same for Y, Z with ȳ, z̄)
//!   over the embedded table, 360–830 nm in Δλ = 1 nm steps; X, Y, Z are then in W·sr⁻¹·m⁻²
//!   (multiply Y by K_m = 683 lm/W for a luminance in cd/m²). Chromaticity
//!   `x = X/(X+Y+Z)`, `y = Y/(X+Y+Z)`.
//! - IEC 61966-2-1 (sRGB): XYZ → linear sRGB with the standard's matrix (D65 white); the
//!   8-bit transfer function lives in [`crate::colour`].
//! - The frequency-shift law (docs/physics.md, "Black body and colour"): `I_ν/ν³` is
//!   invariant along a ray, so a black body at T seen with shift g = ν_obs/ν_emit has the
//!   observed spectrum `g³ B_ν(ν/g, T) = B_ν(ν, g·T)`, a black body at g·T exactly; its
//!   bolometric radiance `σ(gT)⁴/π` scales with g⁴ (Stefan–Boltzmann). [`observed_xyz`]
//!   integrates the transformed spectrum directly, so that tests can check the law rather
//!   than assume it.
//!
//! Colours: [`unit_colour`] is linear sRGB scaled to luminance Y = 1, with out-of-gamut
//! (negative) components clamped to 0; [`colour`] is the same scaled so that its largest
//! component is 1 (the "normalized colour", brightness discarded). [`luminance`] is the
//! physical Y above.
//!
//! The [`BlackbodyTable`] tabulates both on a log-spaced grid in T, [`T_MIN`]..[`T_MAX`]
//! (1000 K to 100 000 K), interpolated linearly in ln T (colour) and in (ln T, ln Y)
//! (luminance). Outside the grid, the colour is clamped to that of the nearer end, and ln Y is
//! extrapolated linearly in ln T with the slope of the end interval (continuous and
//! monotone; below 1000 K a black body is all but invisible anyway). T that is not finite and
//! positive gives black with luminance 0.

use std::sync::OnceLock;

/// Planck constant h, J·s (exact, SI 2019).
pub const PLANCK_H: f64 = 6.626_070_15e-34;
/// Speed of light c, m/s (exact).
pub const SPEED_OF_LIGHT: f64 = 299_792_458.0;
/// Boltzmann constant k_B, J/K (exact, SI 2019).
pub const BOLTZMANN_K: f64 = 1.380_649e-23;
/// Stefan–Boltzmann constant σ = 2π⁵k_B⁴/(15h³c²), W·m⁻²·K⁻⁴.
pub const STEFAN_BOLTZMANN: f64 = 5.670_374_419e-8;

/// IEC 61966-2-1 matrix from CIE XYZ to linear sRGB (D65 white), rows R, G, B.
pub const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// Lowest temperature in the lookup table, K.
pub const T_MIN: f64 = 1000.0;
/// Highest temperature in the lookup table, K.
pub const T_MAX: f64 = 100_000.0;
/// Number of grid points of the lookup table.
pub const TABLE_POINTS: usize = 1024;

/// The CIE 1931 2° colour-matching functions, 1 nm steps (source and licence: `assets/NOTICE.md`).
const CMF_CSV: &str = include_str!("../../../assets/cie1931_2deg_cmf_1nm.csv");
/// Wavelength step of the embedded table, m.
const CMF_STEP_M: f64 = 1e-9;

/// One row of the colour-matching table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CmfSample {
    /// Wavelength, nm.
    pub wavelength_nm: f64,
    /// x̄, ȳ, z̄.
    pub xyz_bar: [f64; 3],
}

/// The CIE 1931 2° colour-matching functions, 360–830 nm in 1 nm steps, parsed once.
pub fn cmf() -> &'static [CmfSample] {
    static TABLE: OnceLock<Vec<CmfSample>> = OnceLock::new();
    TABLE.get_or_init(|| parse_cmf(CMF_CSV))
}

/// Parses the embedded CSV: `#` comment lines, a header line, then
/// `wavelength_nm,xbar,ybar,zbar` rows. The data ship with the binary, so a bad row is a bug.
fn parse_cmf(text: &str) -> Vec<CmfSample> {
    let rows: Vec<CmfSample> = text
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty() && !line.starts_with('#'))
        .skip(1) // header
        .map(|line| {
            let v: Vec<f64> = line
                .split(',')
                .map(|f| f.trim().parse().expect("embedded CMF table: number"))
                .collect();
            assert_eq!(v.len(), 4, "embedded CMF table: 4 columns");
            CmfSample {
                wavelength_nm: v[0],
                xyz_bar: [v[1], v[2], v[3]],
            }
        })
        .collect();
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(
            row.wavelength_nm,
            360.0 + i as f64,
            "embedded CMF table: 1 nm steps"
        );
    }
    rows
}

/// Planck's law per unit wavelength: spectral radiance B_λ(λ, T) in W·sr⁻¹·m⁻³, λ in m, T in K.
pub fn planck_wavelength(lambda_m: f64, t: f64) -> f64 {
    let x = PLANCK_H * SPEED_OF_LIGHT / (lambda_m * BOLTZMANN_K * t);
    2.0 * PLANCK_H * SPEED_OF_LIGHT * SPEED_OF_LIGHT / lambda_m.powi(5) / x.exp_m1()
}

/// Planck's law per unit frequency: B_ν(ν, T) in W·sr⁻¹·m⁻²·Hz⁻¹, ν in Hz, T in K.
pub fn planck_frequency(nu: f64, t: f64) -> f64 {
    let x = PLANCK_H * nu / (BOLTZMANN_K * t);
    2.0 * PLANCK_H * nu.powi(3) / (SPEED_OF_LIGHT * SPEED_OF_LIGHT) / x.exp_m1()
}

/// Integrates a spectral radiance per unit wavelength (W·sr⁻¹·m⁻³, λ in m) against the CIE
/// 1931 colour-matching functions: XYZ in W·sr⁻¹·m⁻².
pub fn spectrum_xyz(spectral_radiance: impl Fn(f64) -> f64) -> [f64; 3] {
    let mut xyz = [0.0; 3];
    for s in cmf() {
        let p = spectral_radiance(s.wavelength_nm * 1e-9) * CMF_STEP_M;
        for (acc, bar) in xyz.iter_mut().zip(s.xyz_bar) {
            *acc += p * bar;
        }
    }
    xyz
}

/// CIE 1931 XYZ of a black body at temperature `t` (K), W·sr⁻¹·m⁻².
pub fn blackbody_xyz(t: f64) -> [f64; 3] {
    spectrum_xyz(|lambda| planck_wavelength(lambda, t))
}

/// CIE 1931 XYZ of a black body at `t` seen with frequency shift `g`, from the transformed
/// spectrum: `I_ν,obs(ν) = g³ B_ν(ν/g, t)`, per wavelength `I_λ = I_ν c/λ²`.
pub fn observed_xyz(g: f64, t: f64) -> [f64; 3] {
    spectrum_xyz(|lambda| {
        let nu = SPEED_OF_LIGHT / lambda;
        g.powi(3) * planck_frequency(nu / g, t) * SPEED_OF_LIGHT / (lambda * lambda)
    })
}

/// Chromaticity (x, y) of XYZ.
pub fn chromaticity(xyz: [f64; 3]) -> (f64, f64) {
    let sum = xyz[0] + xyz[1] + xyz[2];
    (xyz[0] / sum, xyz[1] / sum)
}

/// XYZ → linear sRGB (IEC 61966-2-1), unclamped.
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_SRGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

/// Linear sRGB of XYZ scaled to luminance Y = 1, negative (out-of-gamut) components
/// clamped to 0. Black for Y ≤ 0 or non-finite input.
pub fn unit_rgb(xyz: [f64; 3]) -> [f64; 3] {
    let y = xyz[1];
    if !(y > 0.0 && y.is_finite()) {
        return [0.0; 3];
    }
    xyz_to_linear_srgb(xyz.map(|v| v / y)).map(|c| c.max(0.0))
}

/// Scales a colour so that its largest component is 1 (black stays black).
pub fn normalize_max(rgb: [f64; 3]) -> [f64; 3] {
    let max = rgb[0].max(rgb[1]).max(rgb[2]);
    if max > 0.0 && max.is_finite() {
        rgb.map(|c| c / max)
    } else {
        [0.0; 3]
    }
}

/// Linear sRGB of a black body at `t`, luminance Y = 1 (direct integral).
pub fn unit_colour(t: f64) -> [f64; 3] {
    if !(t > 0.0 && t.is_finite()) {
        return [0.0; 3];
    }
    unit_rgb(blackbody_xyz(t))
}

/// Normalized linear sRGB of a black body at `t`: largest component 1 (direct integral).
pub fn colour(t: f64) -> [f64; 3] {
    normalize_max(unit_colour(t))
}

/// Luminance-weighted radiance Y of a black body at `t`, W·sr⁻¹·m⁻² (direct integral);
/// 0 for T not finite and positive.
pub fn luminance(t: f64) -> f64 {
    if !(t > 0.0 && t.is_finite()) {
        return 0.0;
    }
    blackbody_xyz(t)[1]
}

/// Bolometric radiance of a black body, σT⁴/π in W·sr⁻¹·m⁻².
pub fn bolometric_radiance(t: f64) -> f64 {
    STEFAN_BOLTZMANN * t.powi(4) / std::f64::consts::PI
}

/// One grid point of the table.
#[derive(Clone, Copy, Debug)]
struct Node {
    unit: [f64; 3],
    ln_y: f64,
}

/// Black-body colour and luminance tabulated on a log-spaced grid in T (module docs give the
/// interpolation and the clamping rule).
#[derive(Clone, Debug)]
pub struct BlackbodyTable {
    ln_t_min: f64,
    step: f64,
    nodes: Vec<Node>,
}

impl BlackbodyTable {
    /// Builds the table by direct integration at [`TABLE_POINTS`] temperatures.
    pub fn new() -> BlackbodyTable {
        let ln_t_min = T_MIN.ln();
        let step = (T_MAX.ln() - ln_t_min) / (TABLE_POINTS - 1) as f64;
        let nodes = (0..TABLE_POINTS)
            .map(|i| {
                let t = (ln_t_min + step * i as f64).exp();
                let xyz = blackbody_xyz(t);
                Node {
                    unit: unit_rgb(xyz),
                    ln_y: xyz[1].ln(),
                }
            })
            .collect();
        BlackbodyTable {
            ln_t_min,
            step,
            nodes,
        }
    }

    /// The grid: ln T of the first node and the step in ln T between nodes.
    pub fn grid(&self) -> (f64, f64) {
        (self.ln_t_min, self.step)
    }

    /// The nodes in order: (linear sRGB at luminance 1, ln Y) at each grid temperature (the
    /// viewer's page interpolates them as [`BlackbodyTable::unit_colour`] and
    /// [`BlackbodyTable::luminance`] do).
    pub fn nodes(&self) -> impl Iterator<Item = ([f64; 3], f64)> + '_ {
        self.nodes.iter().map(|n| (n.unit, n.ln_y))
    }

    /// Grid position of ln T: interval index and unclamped fraction within it.
    fn locate(&self, t: f64) -> (usize, f64) {
        let s = (t.ln() - self.ln_t_min) / self.step;
        let last = self.nodes.len() - 2;
        let i = (s.floor().max(0.0) as usize).min(last);
        (i, s - i as f64)
    }

    /// Linear sRGB at luminance Y = 1 of a black body at `t` (black if `t` is not finite
    /// and positive); outside the grid, the colour of the nearer end.
    pub fn unit_colour(&self, t: f64) -> [f64; 3] {
        if !(t > 0.0 && t.is_finite()) {
            return [0.0; 3];
        }
        let (i, f) = self.locate(t);
        let f = f.clamp(0.0, 1.0);
        let (a, b) = (self.nodes[i].unit, self.nodes[i + 1].unit);
        [0, 1, 2].map(|k| a[k] + f * (b[k] - a[k]))
    }

    /// Normalized linear sRGB (largest component 1) of a black body at `t`.
    pub fn colour(&self, t: f64) -> [f64; 3] {
        normalize_max(self.unit_colour(t))
    }

    /// Luminance Y of a black body at `t`, W·sr⁻¹·m⁻²; 0 if `t` is not finite and positive.
    /// Outside the grid ln Y is extrapolated linearly in ln T.
    pub fn luminance(&self, t: f64) -> f64 {
        if !(t > 0.0 && t.is_finite()) {
            return 0.0;
        }
        let (i, f) = self.locate(t);
        let (a, b) = (self.nodes[i].ln_y, self.nodes[i + 1].ln_y);
        (a + f * (b - a)).exp()
    }
}

impl Default for BlackbodyTable {
    fn default() -> Self {
        BlackbodyTable::new()
    }
}

/// The shared table, built on first use.
pub fn table() -> &'static BlackbodyTable {
    static TABLE: OnceLock<BlackbodyTable> = OnceLock::new();
    TABLE.get_or_init(BlackbodyTable::new)
}
