//! Light rays connecting a light source at rest with an event ("shadow rays"): all
//! future-directed null geodesics from the source's worldline to a target event, up to a
//! given number of windings.
//!
//! For a source on the axis (worldline r = 0, z = 0) every such ray is a closed form through
//! the axis (Novello, Soares & Tiomno, PRD 27, 779 (1983), Sec. III; Grave et al., PRD 80,
//! 103002 (2009), Sec. III; see [`crate::closed_form`]). A photon with E = 1 leaving at
//! angle ψ to the z axis (c = cos ψ) has ω = √(1+c²)/(2a), r_max = 2a √((1−c²)/(1+c²)),
//! q = √(2/(1+c²)), and r = r_max sin(ωλ), z = cλ. It meets the target at cylindrical
//! (ρ, φ_P, z_P) when, for a winding n ≥ 0 and branch b,
//!
//!   θ = nπ + θ0,  θ0 = arcsin(ρ/r_max) (outbound) or π − arcsin(ρ/r_max) (inbound),
//!   F(c) = 2a c θ(c)/√(1+c²) − z_P = 0,  sign c = sign z_P,  c² ≤ (1 − s²)/(1 + s²),
//!
//! s = ρ/2a, so rays exist only for ρ < 2a (ρ = 2a tangentially). Then λ = θ/ω, the
//! emission azimuth is χ = φ_P − Φ(θ) + nπ and the emission time t_P − (2√2 a Φ(θ) − λ).
//! F is solved per (n, b) by bracketing on a grid in |c| and refining in ψ (which resolves
//! the nearly vertical rays near the axis); for z_P = 0 the only root is c = 0 (in-plane
//! rays, exactly two per winding).
//!
//! A source at rest elsewhere is reduced to this case by the isometry T_S sending it to the
//! origin ([`crate::isometry`]): its worldline goes to the axis worldline with t unchanged.

use crate::closed_form::OriginGeodesic;
use crate::geodesic::refine_root;
use crate::isometry::{disc, Isometry};
use crate::metric::Spacetime;
use crate::vectors::{Event, FourVector};
use std::f64::consts::{PI, SQRT_2};

/// Which half of the loop meets the target: on the way out to r_max or back in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Branch {
    Outbound,
    Inbound,
}

impl Branch {
    /// `outbound` or `inbound`, as printed.
    pub fn name(self) -> &'static str {
        match self {
            Branch::Outbound => "outbound",
            Branch::Inbound => "inbound",
        }
    }
}

/// One light ray from the source to the target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowRay {
    /// The emission event on the source's worldline.
    pub emission: Event,
    /// The future-directed null tangent at emission, normalized to E = −k_t = 1.
    pub tangent: FourVector,
    /// Affine parameter from emission to the target.
    pub lambda: f64,
    /// Completed returns to the source's axis before reaching the target.
    pub winding: u32,
    pub branch: Branch,
}

/// Grid cells per (winding, branch) used to bracket the roots of F.
const GRID: usize = 256;

/// Φ(θ) = arctan(q tan θ), continuous in θ.
fn big_phi(q: f64, th: f64) -> f64 {
    let (s, c) = th.sin_cos();
    th + ((q - 1.0) * s * c).atan2(c * c + q * s * s)
}

/// θ of a winding and branch for a target at distance `rho`, for the ray leaving at angle ψ
/// to the z axis given as (cos ψ, sin ψ) = (c, σ) (needs r_max ≥ ρ). r_max = 2a σ/√(1 + c²)
/// is the closed form's 2a √((1 − c²)/(1 + c²)) without the cancellation in 1 − c².
fn theta(a: f64, rho: f64, (c, sigma): (f64, f64), n: u32, b: Branch) -> f64 {
    theta_of(first_theta(a, rho, (c, sigma)), n, b)
}

/// θ of the first outbound meeting, arcsin(ρ/r_max): the same for every winding and branch.
fn first_theta(a: f64, rho: f64, (c, sigma): (f64, f64)) -> f64 {
    let r_max = 2.0 * a * sigma / (1.0 + c * c).sqrt();
    (rho / r_max).min(1.0).asin()
}

/// θ of a winding and branch from [`first_theta`].
fn theta_of(th0: f64, n: u32, b: Branch) -> f64 {
    n as f64 * PI
        + match b {
            Branch::Outbound => th0,
            Branch::Inbound => PI - th0,
        }
}

/// The ray leaving at angle ψ to the z axis, given as (c, σ) = (cos ψ, sin ψ) with c signed
/// (toward the target's side), for a winding and branch.
fn ray(a: f64, target: Event, (c, sigma): (f64, f64), n: u32, b: Branch) -> ShadowRay {
    let rho = target.r();
    let th = theta(a, rho, (c, sigma), n, b);
    let w1 = 1.0 + c * c;
    let omega = w1.sqrt() / (2.0 * a);
    let q = (2.0 / w1).sqrt();
    let big = big_phi(q, th);
    let lambda = th / omega;
    let chi = target.phi() - big + n as f64 * PI;
    ShadowRay {
        emission: Event::new(target.t - (2.0 * SQRT_2 * a * big - lambda), 0.0, 0.0, 0.0),
        tangent: FourVector::new(1.0, sigma * chi.cos(), sigma * chi.sin(), c),
        lambda,
        winding: n,
        branch: b,
    }
}

/// All light rays from the source at rest on the axis (r = 0, z = 0) of the Gödel metric
/// with parameter `a` to `target`, with windings 0..=`max_winding`, latest emission first.
/// Empty when the target lies at or beyond the horizon distance ρ ≥ 2a.
///
/// The roots are bracketed on the grid of [`GRID`] cells in |c| ∈ [0, c_max] and refined in
/// the angle ψ = arccos |c|: near the axis (ρ ≪ a) the ray that climbs almost along z has
/// 1 − |c| ~ ρ²/a², below what f64 resolves of c near 1 (at ρ = 10⁻⁹ a it missed the target
/// by 1.2 a), while ψ ~ ρ/a is resolved, and c, sin ψ and r_max follow from ψ without
/// cancellation. The grid's last point is ψ_min, where r_max = ρ, from s = ρ/2a directly.
pub fn shadow_rays_from_axis(a: f64, target: Event, max_winding: u32) -> Vec<ShadowRay> {
    rays_from_axis(a, target, max_winding, f64::INFINITY)
}

/// A lower bound of the travel time t_P − t_emission = 2√2·a·Φ(θ) − λ of every ray of
/// winding n whose |c| is at least `c_lo`: θ ∈ [nπ, (n + 1)π], where Φ(θ) ≥ nπ (Φ(nπ) = nπ
/// and Φ' > 0), and λ = 2aθ/√(1 + c²). It grows with n and with c_lo.
fn travel_floor(a: f64, n: u32, c_lo: f64) -> f64 {
    let n = n as f64;
    2.0 * a * PI * (SQRT_2 * n - (n + 1.0) / (1.0 + c_lo * c_lo).sqrt())
}

/// The largest |c| at which a ray of winding n may travel at most `max_travel`
/// ([`travel_floor`] solved for c_lo; infinite where every |c| may).
fn c_within(a: f64, n: u32, max_travel: f64) -> f64 {
    let nf = n as f64;
    let gap = SQRT_2 * nf - max_travel / (2.0 * a * PI);
    if gap.is_nan() || gap <= 0.0 {
        return f64::INFINITY;
    }
    let root = (nf + 1.0) / gap; // √(1 + c²) at the bound
    (root * root - 1.0).max(0.0).sqrt()
}

/// [`shadow_rays_from_axis`] without the rays whose travel time exceeds `max_travel`: the
/// grid's cells (and windings) where [`travel_floor`] exceeds it are not searched, and the
/// rays found there otherwise are left out (some may be too).
fn rays_from_axis(a: f64, target: Event, max_winding: u32, max_travel: f64) -> Vec<ShadowRay> {
    let rho = target.r();
    let s = rho / (2.0 * a);
    if !target.is_finite() || s * s >= 1.0 {
        return Vec::new();
    }
    // c_max² = (1 − s²)/(1 + s²) and sin²ψ_min = 2s²/(1 + s²).
    let c_max = ((1.0 - s * s) / (1.0 + s * s)).sqrt();
    let psi_min = (s * SQRT_2).atan2((1.0 - s * s).sqrt());
    let zp = target.z;
    let sign = zp.signum();
    // Grid point i: |c| = c_max i/GRID as (c, σ), the last one (c_max, sin ψ_min) exactly; the
    // points' ψ only where a root is refined.
    let point = |i: usize| match i {
        GRID => (c_max, psi_min.sin()),
        _ => {
            let c = c_max * i as f64 / GRID as f64;
            (c, (1.0 - c * c).sqrt())
        }
    };
    let psi_of = |i: usize| match i {
        GRID => psi_min,
        _ => (c_max * i as f64 / GRID as f64).acos(),
    };
    // What the grid's G needs of each point, the same for every winding and branch (made
    // once: this is most of the work per target).
    let grid: [(f64, f64, f64); GRID + 1] = std::array::from_fn(|i| {
        let (c, sigma) = point(i);
        (c, first_theta(a, rho, (c, sigma)), (1.0 + c * c).sqrt())
    });
    // The inbound G at grid point i as a line in the winding n: G = n·slope + at0, slope =
    // 2aπ·c/√(1 + c²) and at0 = 2a·c·(π − θ₀)/√(1 + c²) − |z_P| (θ = nπ + π − θ₀).
    let lines: [(f64, f64); GRID + 1] = std::array::from_fn(|i| {
        let (c, th0, root) = grid[i];
        let k = 2.0 * a * c / root;
        (k * PI, k * (PI - th0) - target.z.abs())
    });
    let mut out = Vec::new();
    for n in 0..=max_winding {
        if travel_floor(a, n, 0.0) > max_travel {
            break; // and every later winding
        }
        // The cells whose smaller |c| (c_max·(i − 1)/GRID) may hold a ray within the travel
        // time, one more for rounding; the others' rays all take longer.
        let c_hi = c_within(a, n, max_travel);
        let last_cell = if c_hi >= c_max {
            GRID
        } else {
            ((c_hi / c_max * GRID as f64).floor() as usize + 2).min(GRID)
        };
        for b in [Branch::Outbound, Branch::Inbound] {
            if zp == 0.0 {
                out.push(ray(a, target, (0.0, 1.0), n, b));
                continue;
            }
            // G = 2a |c| θ/√(1+c²) − |z_P| for |c| ∈ [0, c_max], as (c, σ) and as ψ; G(0) < 0.
            let g_at = |(c, sigma): (f64, f64)| {
                2.0 * a * c * theta(a, rho, (c, sigma), n, b) / (1.0 + c * c).sqrt() - zp.abs()
            };
            let g = |psi: f64| {
                let (sigma, c) = psi.sin_cos();
                g_at((c, sigma))
            };
            // g_at at grid point i, from its parts made above.
            let g_grid = |i: usize| {
                let (c, th0, root) = grid[i];
                2.0 * a * c * theta_of(th0, n, b) / root - zp.abs()
            };
            let signed = |(c, sigma): (f64, f64)| (sign * c, sigma);
            // The root in cell i (between grid points i − 1 and i, G there g0 and g1), if any.
            let mut root_in = |i: usize, g0: f64, g1: f64| {
                // A root exactly at c_max belongs to both branches: count it once.
                let at_join = i == GRID && b == Branch::Inbound;
                if g1 == 0.0 && !at_join {
                    out.push(ray(a, target, signed(point(i)), n, b));
                } else if g0 < 0.0 && g1 > 0.0 || g0 > 0.0 && g1 < 0.0 {
                    // ψ falls as |c| grows: the cell is [ψ_i, ψ_(i−1)].
                    let psi = refine_root(g, psi_of(i), psi_of(i - 1), g1, g0);
                    let (sigma, c) = psi.sin_cos();
                    out.push(ray(a, target, signed((c, sigma)), n, b));
                }
            };
            if b == Branch::Outbound {
                // On the way out G grows with |c| (c/√(1 + c²) grows, and θ₀ = arcsin(ρ/r_max)
                // with it as r_max falls), from G(0) = −|z_P| < 0: its one root lies in the
                // first cell whose end is not negative, found by bisecting the grid's indices
                // (the scan's cell, from the same values).
                let end = g_grid(last_cell);
                if end.is_nan() || end < 0.0 {
                    continue; // no root up to the last cell (or G is NaN there)
                }
                let (mut lo, mut hi) = (0, last_cell);
                while hi - lo > 1 {
                    let mid = (lo + hi) / 2;
                    if g_grid(mid) < 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                root_in(hi, g_grid(hi - 1), g_grid(hi));
                continue;
            }
            // On the way back G may rise and fall: every cell is looked at. G at a grid point
            // is linear in the winding n (`lines`), so a cell whose ends lie clear of 0 on one
            // side (by far more than G's rounding) holds no root and needs no G; the others
            // get the same G as a scan of every cell, in the same order.
            let nf = n as f64;
            let clear = 1e-9 * (2.0 * a * PI * (nf + 1.0) + zp.abs());
            let side = |i: usize| {
                let (slope, at0) = lines[i];
                let e = nf * slope + at0;
                if e > clear {
                    1
                } else if e < -clear {
                    -1
                } else {
                    0
                }
            };
            let mut s0 = side(0);
            for i in 1..=last_cell {
                let s1 = side(i);
                if s0 == 0 || s1 != s0 {
                    root_in(i, g_grid(i - 1), g_grid(i));
                }
                s0 = s1;
            }
        }
    }
    out.sort_by(|p, q| q.emission.t.total_cmp(&p.emission.t));
    out
}

/// All light rays from a source at rest at `source` (its x, y, z; t ignored) to `target`:
/// the axis case after mapping the source to the origin, mapped back.
pub fn shadow_rays(a: f64, source: Event, target: Event, max_winding: u32) -> Vec<ShadowRay> {
    mapped_back(a, source, target, |at| {
        shadow_rays_from_axis(a, at, max_winding)
    })
}

/// The rays of [`shadow_rays`] emitted at most `window` (coordinate time) before `target`:
/// the grid is not searched where every ray would be emitted earlier.
pub fn shadow_rays_within(
    a: f64,
    source: Event,
    target: Event,
    window: f64,
    max_winding: u32,
) -> Vec<ShadowRay> {
    // The map to the source's axis moves the target's time against the source's clock by
    // 2√2·a·arg(1 − w̄_S w) with |arg| < π/2: a ray that travels longer than the window and
    // √2·π·a there is emitted before the window (twice that margin, for rounding).
    let max_travel = window + 2.0 * SQRT_2 * PI * a;
    let mut rays = mapped_back(a, source, target, |at| {
        rays_from_axis(a, at, max_winding, max_travel)
    });
    rays.retain(|r| r.emission.t >= target.t - window);
    rays
}

/// The rays `from_axis` finds to the target moved to the source's axis, mapped back.
fn mapped_back(
    a: f64,
    source: Event,
    target: Event,
    from_axis: impl FnOnce(Event) -> Vec<ShadowRay>,
) -> Vec<ShadowRay> {
    let to = Isometry::to_origin(a, Event::new(0.0, source.x, source.y, source.z));
    // T_S keeps t on the source worldline: arg(1 − |w_S|²) = 0.
    debug_assert!(disc(a, source.x, source.y).norm_sqr() < 1.0);
    let back = to.inverse();
    from_axis(to.apply(target))
        .into_iter()
        .map(|r| ShadowRay {
            emission: back.apply(r.emission),
            tangent: back.push(r.emission, r.tangent),
            ..r
        })
        .collect()
}

/// The source's area distance squared, D² = dA/dΩ, of a light ray from a source at rest at
/// `source`: the cross-section dA at the ray's end of the bundle leaving the source into
/// the solid angle dΩ (measured in the source's rest frame). A point source of luminosity
/// L then gives the energy flux L g²/(4π D²) across the ray at the receiver (Etherington's
/// reciprocity: Etherington, Phil. Mag. 15, 761 (1933); Ellis, Gen. Rel. Grav. 39, 1047
/// (2007); docs/physics.md, "Area distance and irradiance"; g = ν_received/ν_emitted).
///
/// Computed in the frame where the source sits on the axis (docs/physics.md, "Isometries":
/// the isometry preserves the metric, the affine parameter and static frames). There the
/// bundle's directions are (ψ, χ) with k = (1, sin ψ cos χ, sin ψ sin χ, cos ψ), and the two
/// Jacobi fields at the ray's end are J_χ = ∂_φ (rotation about the axis, a Killing field:
/// exact) and J_ψ by a central difference of the closed form (error ~1e-10). Both are orthogonal
/// to the ray's tangent (they vanish at emission), so the area √det g(J_i, J_j) is the same
/// for every observer (Sachs). D² = area/sin ψ. NaN where the ray leaves along ±z (sin ψ = 0:
/// the parametrization degenerates) or `ray` is not from `source`.
pub fn source_area_distance_sq(a: f64, source: Event, ray: &ShadowRay) -> f64 {
    let to = Isometry::to_origin(a, Event::new(0.0, source.x, source.y, source.z));
    let k = to.push(ray.emission, ray.tangent);
    let chi = k.y.atan2(k.x);
    let psi = (k.x * k.x + k.y * k.y).sqrt().atan2(k.z);
    let end = |psi: f64| {
        let k = FourVector::new(1.0, psi.sin() * chi.cos(), psi.sin() * chi.sin(), psi.cos());
        OriginGeodesic::new(a, k).map(|g| g.at(ray.lambda).0)
    };
    const H: f64 = 1e-5;
    let (Some(x), Some(xp), Some(xm)) = (end(psi), end(psi + H), end(psi - H)) else {
        return f64::NAN;
    };
    let j_psi = (xp - xm).to_array().map(|c| c / (2.0 * H));
    let j_chi = [0.0, -x.y, x.x, 0.0];
    let g = crate::godel::Godel::new(a);
    let dot =
        |u: [f64; 4], v: [f64; 4]| g.dot(x, FourVector::from_array(u), FourVector::from_array(v));
    let det = dot(j_psi, j_psi) * dot(j_chi, j_chi) - dot(j_psi, j_chi).powi(2);
    det.max(0.0).sqrt() / psi.sin()
}
