//! Tests of the black-body colour science: Planck's law, CIE 1931 chromaticities against
//! published Planckian-locus values, the frequency-shift law, and the lookup table.

use shade::blackbody::{
    self, blackbody_xyz, bolometric_radiance, chromaticity, cmf, observed_xyz, planck_frequency,
    planck_wavelength, table, T_MAX, T_MIN,
};

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn cmf_table_is_complete() {
    let t = cmf();
    assert_eq!(t.len(), 471);
    assert_eq!(t[0].wavelength_nm, 360.0);
    assert_eq!(t[470].wavelength_nm, 830.0);
    // ȳ peaks at 555 nm with value 1 (the photopic luminosity function).
    let peak = t
        .iter()
        .max_by(|a, b| a.xyz_bar[1].total_cmp(&b.xyz_bar[1]))
        .unwrap();
    assert_eq!(peak.wavelength_nm, 555.0);
    assert!((peak.xyz_bar[1] - 1.0).abs() < 1e-6);
}

#[test]
fn planck_peaks_where_wien_says_and_integrates_to_stefan_boltzmann() {
    // Wien's displacement law: λ_max T = 2.897771955e-3 m·K.
    let t = 5000.0;
    let peak = (1..20_000)
        .map(|i| i as f64 * 0.1e-9)
        .max_by(|a, b| planck_wavelength(*a, t).total_cmp(&planck_wavelength(*b, t)))
        .unwrap();
    assert!((peak * t - 2.897_771_955e-3).abs() < 1e-9 * t, "{peak}");
    // ∫B_λ dλ = σT⁴/π (midpoint rule in ln λ over 10 nm .. 1 m).
    for t in [300.0, 5000.0, 40_000.0] {
        let n = 200_000;
        let (a, b) = ((10e-9f64).ln(), (1.0f64).ln());
        let h = (b - a) / n as f64;
        let integral: f64 = (0..n)
            .map(|i| {
                let lambda = (a + h * (i as f64 + 0.5)).exp();
                planck_wavelength(lambda, t) * lambda * h
            })
            .sum();
        let r = rel(integral, bolometric_radiance(t));
        assert!(r < 1e-6, "T = {t}: relative error {r}");
    }
}

/// Published chromaticities (x, y) of the Planckian locus, CIE 1931 2° observer. Values as
/// tabulated in Wyszecki & Stiles, "Color Science", 2nd ed. (Wiley 1982), and reproduced to
/// 1e-4 by the cubic-spline fit of Kim et al., "Design of advanced color temperature control
/// system for HDTV applications", J. Korean Phys. Soc. 41, 865 (2002): 2000 K (0.5269,
/// 0.4133), 4000 K (0.3805, 0.3767), 6500 K (0.3135, 0.3237), 10000 K (0.2807, 0.2883).
const PUBLISHED: [(f64, f64, f64); 4] = [
    (2000.0, 0.5267, 0.4133),
    (4000.0, 0.3805, 0.3768),
    (6500.0, 0.3135, 0.3237),
    (10_000.0, 0.2807, 0.2884),
];

#[test]
fn chromaticities_match_the_published_planckian_locus() {
    for (t, x0, y0) in PUBLISHED {
        let (x, y) = chromaticity(blackbody_xyz(t));
        let err = (x - x0).abs().max((y - y0).abs());
        println!("T = {t} K: (x, y) = ({x:.5}, {y:.5}), published ({x0}, {y0}), error {err:.1e}");
        assert!(err < 2e-3, "T = {t}: ({x}, {y}) vs ({x0}, {y0})");
    }
}

#[test]
fn colour_runs_from_red_to_blue() {
    let red = blackbody::colour(2000.0);
    let blue = blackbody::colour(20_000.0);
    assert_eq!(red[0], 1.0);
    assert!(red[2] < 0.05, "{red:?}");
    assert_eq!(blue[2], 1.0);
    assert!(blue[0] < 0.6, "{blue:?}");
    // Largest component is 1, none negative.
    for t in [1000.0, 3000.0, 6504.0, 50_000.0] {
        let c = blackbody::colour(t);
        assert_eq!(c.iter().cloned().fold(0.0, f64::max), 1.0);
        assert!(c.iter().all(|&v| v >= 0.0), "{t}: {c:?}");
    }
}

#[test]
fn a_6504_kelvin_black_body_is_near_white() {
    // The Planckian 6504 K point lies slightly below D65 (towards magenta), so green is the
    // lowest component: linear spread ≈ 0.057, encoded (sRGB) spread ≈ 0.025.
    let c = blackbody::colour(6504.0);
    let spread = |c: [f64; 3]| {
        let max = c.iter().cloned().fold(f64::MIN, f64::max);
        let min = c.iter().cloned().fold(f64::MAX, f64::min);
        max - min
    };
    println!("6504 K: linear sRGB {c:?}");
    assert!(spread(c) < 0.06, "{c:?}");
    let encoded = c.map(|v| f64::from(shade::colour::linear_to_srgb(v as f32)));
    assert!(spread(encoded) < 0.03, "{encoded:?}");
}

#[test]
fn shifted_planck_spectrum_is_a_planck_spectrum_at_g_t() {
    // g³ B_ν(ν/g, T) = B_ν(ν, gT) for every ν.
    for g in [0.3, 0.5, 0.9, 1.0, 1.7, 2.0, 4.0] {
        for t in [1500.0, 5800.0, 30_000.0] {
            for nu in [1e13, 3e14, 5.45e14, 1e15, 3e15] {
                let shifted = g * g * g * planck_frequency(nu / g, t);
                let direct = planck_frequency(nu, g * t);
                assert!(rel(shifted, direct) < 1e-12, "g {g} T {t} ν {nu}");
            }
        }
    }
}

#[test]
fn colour_and_luminance_at_g_t_are_those_of_the_observed_spectrum() {
    for g in [0.4, 0.5, 0.8, 1.25, 2.0, 3.0] {
        for t in [2500.0, 5000.0, 12_000.0] {
            let observed = observed_xyz(g, t);
            let direct = blackbody_xyz(g * t);
            for k in 0..3 {
                assert!(rel(observed[k], direct[k]) < 1e-10, "g {g} T {t} k {k}");
            }
            let (c_obs, c_dir) = (
                blackbody::normalize_max(blackbody::unit_rgb(observed)),
                blackbody::colour(g * t),
            );
            for k in 0..3 {
                assert!((c_obs[k] - c_dir[k]).abs() < 1e-12, "g {g} T {t}");
            }
        }
    }
}

#[test]
fn bolometric_radiance_of_the_observed_spectrum_scales_with_g_to_the_fourth() {
    // ∫ g³ B_ν(ν/g, T) dν over ν (midpoint rule in ln ν) equals g⁴ σT⁴/π.
    let t = 4000.0;
    let integral = |g: f64| {
        let n = 200_000;
        let (a, b) = ((1e9f64).ln(), (1e17f64).ln());
        let h = (b - a) / n as f64;
        (0..n)
            .map(|i| {
                let nu = (a + h * (i as f64 + 0.5)).exp();
                g.powi(3) * planck_frequency(nu / g, t) * nu * h
            })
            .sum::<f64>()
    };
    let unshifted = integral(1.0);
    assert!(rel(unshifted, bolometric_radiance(t)) < 1e-6);
    for g in [0.25, 0.5, 2.0, 5.0] {
        let r = rel(integral(g), g.powi(4) * unshifted);
        assert!(r < 1e-6, "g {g}: {r}");
    }
}

#[test]
fn table_matches_the_direct_integral_across_its_range() {
    let tab = table();
    let n = 997; // off the grid points
    let (mut worst_colour, mut worst_y) = (0.0f64, 0.0f64);
    for i in 0..=n {
        let t = T_MIN * (T_MAX / T_MIN).powf(i as f64 / n as f64);
        let (a, b) = (tab.colour(t), blackbody::colour(t));
        for k in 0..3 {
            worst_colour = worst_colour.max((a[k] - b[k]).abs());
        }
        worst_y = worst_y.max(rel(tab.luminance(t), blackbody::luminance(t)));
    }
    println!("table: worst colour error {worst_colour:.1e}, worst relative Y error {worst_y:.1e}");
    assert!(worst_colour < 1e-3, "{worst_colour}");
    assert!(worst_y < 1e-3, "{worst_y}");
}

#[test]
fn table_clamps_outside_its_range() {
    let tab = table();
    assert_eq!(tab.colour(500.0), tab.colour(T_MIN));
    assert_eq!(tab.colour(1e7), tab.colour(T_MAX));
    // Luminance keeps falling below the range and rising above it.
    assert!(tab.luminance(500.0) < tab.luminance(T_MIN));
    assert!(tab.luminance(500.0) > 0.0);
    assert!(tab.luminance(1e6) > tab.luminance(T_MAX));
    // Continuous at the ends.
    assert!(rel(tab.luminance(T_MIN * (1.0 - 1e-9)), tab.luminance(T_MIN)) < 1e-6);
    assert!(rel(tab.luminance(T_MAX * (1.0 + 1e-9)), tab.luminance(T_MAX)) < 1e-6);
    // Not a temperature: black.
    for t in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        assert_eq!(tab.colour(t), [0.0; 3]);
        assert_eq!(tab.luminance(t), 0.0);
    }
}

#[test]
fn luminance_rises_with_temperature() {
    let tab = table();
    let mut last = 0.0;
    for i in 0..200 {
        let t = 300.0 * 1.04f64.powi(i);
        let y = tab.luminance(t);
        assert!(y > last, "T = {t}");
        last = y;
    }
}
