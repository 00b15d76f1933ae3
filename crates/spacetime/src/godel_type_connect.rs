//! Light rays connecting a light source at rest with an event ("shadow rays") in every
//! member of the Gödel-type family (`GodelType`): all future-directed null geodesics from
//! the source's static worldline to a target event, up to a given number of windings, and
//! the source's area distance along each (docs/physics.md, "The Gödel-type family",
//! subsection "Shadow rays in the family"). Gödel's version is `connect.rs`, whose
//! conventions (ShadowRay, branches, windings, E = 1) this file follows.
//!
//! From the axis a photon with E = 1 leaving at angle ψ to the z axis, k = (1, σ cos χ,
//! σ sin χ, c) with (c, σ) = (cos ψ, sin ψ), has (`godel_type_geodesic.rs`) Λ = Ω² − m²σ²/4
//! and w = sinh(mρ/2) = (m/2) σ S1(λ) (sin(μρ/2) for m² = −μ², ρ for m² = 0), z = cλ. In the
//! Gödel-like radius R = (2/m) sinh(mρ/2) the condition ρ(λ) = ρ_P is σ S1(λ) = R_P:
//!
//!   returning (Λ > 0): sin θ = √Λ R_P/σ, θ = √Λ λ = nπ + θ0 (outbound) or nπ + π − θ0
//!     (inbound), θ0 = arcsin(√Λ R_P/σ), which needs σ ≥ σ_min = Ω|ζ_P|, |ζ_P| = R_P/
//!     cosh(mρ_P/2) = (2/m) tanh(mρ_P/2) the base coordinate's modulus (cos for m² < 0);
//!   escaping (Λ ≤ 0, only for m² ≥ 4Ω² and σ ≥ 2Ω/m): S1 = sinh(√−Λ λ)/√−Λ (λ at Λ = 0)
//!     grows monotonically, so the ray crosses each radius once, outward: λ = asinh(√−Λ
//!     R_P/σ)/√−Λ, counted as the outbound branch of winding 0.
//!
//! So a target is reached only if σ_min ≤ 1, i.e. ρ_P < ρ_c for m² < 4Ω² (Gödel: r < 2a) and
//! everywhere for causal members. The remaining condition is F(c) = c λ(c) − z_P = 0 with
//! sign c = sign z_P, solved per (winding, branch) as in `connect.rs`: bracketed on a grid
//! uniform in |c| from the lowest |c| of the branch (0, or c_esc = √(1 − 4Ω²/m²) for the
//! returning-only branches of members with m² > 4Ω², where λ → ∞) to c_max = cos ψ_min, and
//! refined in ψ. For z_P = 0 only c = 0 solves it (in-plane rays). The emission azimuth is
//! the target's minus the angle the closed form has turned, and the emission time t_P minus
//! the closed form's t(λ).
//!
//! A target on the source's axis (ρ_P = 0) is a caustic: the straight ray along z reaches
//! it, and every returning ray whose z at its n-th return is z_P, from any azimuth (a cone);
//! each cone is given once, at azimuth 0, as the inbound branch of winding n − 1.
//!
//! A source at rest elsewhere is reduced to the axis by the isometry T_S of
//! `godel_type_symmetry.rs`: t′ = t − t_S − χ(ζ) with χ depending on ζ alone, so T_S commutes
//! with t-translations, and χ(ζ_S) = (Ω/k) arg(1 − k|ζ_S|²) = 0 (1 − k|ζ_S|² > 0), so the
//! source's worldline goes to the axis worldline with t′ = t − t_S. On the sphere (m² < 0)
//! the principal time shift of the map back may put the target 8πΩ/μ² off along the ray (the
//! cut, `TypeExactGeodesic`): the emission time is corrected by the whole periods that the
//! continued closed form from the emission event finds.

// `!(a < b)` is "not a < b, NaN included": NaN constants and targets must give no rays.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::connect::{Branch, ShadowRay};
use crate::geodesic::refine_root;
use crate::godel_chart::GodelChart;
use crate::godel_type::GodelType;
use crate::godel_type_geodesic::{TypeExactGeodesic, TypeOriginGeodesic};
use crate::godel_type_symmetry::{base_coordinate, TypeIsometry};
use crate::metric::Spacetime;
use crate::vectors::{Event, FourVector};
use std::f64::consts::PI;

/// Grid cells per (winding, branch) used to bracket the roots of F.
const GRID: usize = 256;

/// Λ = Ω² − m²σ²/4 written as Ω²c² + (Ω² − m²/4)σ², without the cancellation near c = 0
/// for m² ≈ 4Ω² (c² + σ² = 1).
fn big_lambda(member: GodelType, (c, sigma): (f64, f64)) -> f64 {
    let w2 = member.omega * member.omega;
    w2 * c * c + (w2 - 0.25 * member.m2) * sigma * sigma
}

/// The affine parameter at which the ray leaving at (c, σ) (c ≥ 0) is at the Gödel-like
/// radius `r` on a winding and branch, or `None` where that branch does not exist (escaping
/// rays have only the outbound branch of winding 0; σ = 0 only reaches r = 0).
fn lambda_at(member: GodelType, r: f64, (c, sigma): (f64, f64), n: u32, b: Branch) -> Option<f64> {
    let lam = big_lambda(member, (c, sigma));
    if lam > 0.0 {
        let root = lam.sqrt();
        let s = if r == 0.0 {
            0.0
        } else if sigma == 0.0 {
            return None;
        } else {
            (root * r / sigma).min(1.0)
        };
        let th0 = s.asin();
        let th = n as f64 * PI
            + match b {
                Branch::Outbound => th0,
                Branch::Inbound => PI - th0,
            };
        Some(th / root)
    } else if n == 0 && b == Branch::Outbound && sigma > 0.0 {
        let x = r / sigma;
        let root = (-lam).sqrt();
        Some(if root == 0.0 {
            x
        } else {
            (root * x).asinh() / root
        })
    } else {
        None
    }
}

/// G = |c| λ − |z_P| on a branch at (c, σ), with its limits where λ → ∞ (Λ → 0 from above):
/// +∞ for c > 0, and θ/Ω at c = 0 (only for m² = 4Ω², where Λ = Ω²c², so cλ = θ/Ω, and
/// θ₀ = arcsin(Ωc R/σ) → 0 leaves θ = nπ outbound, (n + 1)π inbound). NaN (no root) where
/// the branch does not exist.
fn excess(member: GodelType, r: f64, zp: f64, (c, sigma): (f64, f64), n: u32, b: Branch) -> f64 {
    match lambda_at(member, r, (c, sigma), n, b) {
        Some(l) if l.is_finite() => c * l - zp.abs(),
        _ if big_lambda(member, (c, sigma)) <= 0.0 && !(n == 0 && b == Branch::Outbound) => {
            if c > 0.0 {
                f64::INFINITY
            } else {
                let th = n as f64 * PI
                    + match b {
                        Branch::Outbound => 0.0,
                        Branch::Inbound => PI,
                    };
                th / member.omega - zp.abs()
            }
        }
        _ => f64::NAN,
    }
}

/// The ray leaving at (c, σ) (c signed) reaching `target` at parameter `lambda`: the closed
/// form from azimuth 0 is rotated so that it ends at the target's azimuth, and started so
/// that it ends at the target's t.
fn ray(
    member: GodelType,
    target: Event,
    (c, sigma): (f64, f64),
    lambda: f64,
    n: u32,
    b: Branch,
) -> Option<ShadowRay> {
    let g = TypeOriginGeodesic::new(member, FourVector::new(1.0, sigma, 0.0, c))?;
    let (end, _) = g.at(lambda);
    // On the axis (r = 0) any azimuth serves: 0.
    let alpha = if target.x == 0.0 && target.y == 0.0 {
        0.0
    } else {
        target.y.atan2(target.x) - end.y.atan2(end.x)
    };
    let r = ShadowRay {
        emission: Event::new(target.t - end.t, 0.0, 0.0, 0.0),
        tangent: FourVector::new(1.0, sigma * alpha.cos(), sigma * alpha.sin(), c),
        lambda,
        winding: n,
        branch: b,
    };
    (r.emission.is_finite() && r.tangent.is_finite()).then_some(r)
}

/// All light rays from the source at rest on the axis (ρ = 0, z = 0) of `member` to
/// `target`, with windings 0..=`max_winding`, latest emission first. Empty where no ray
/// reaches the target (ρ_P ≥ ρ_c for m² < 4Ω², the target outside the chart or not finite,
/// or the target on the source's worldline).
pub fn type_shadow_rays_from_axis(
    member: GodelType,
    target: Event,
    max_winding: u32,
) -> Vec<ShadowRay> {
    let mut out = Vec::new();
    let rho = target.r();
    let outside = member.coordinate_radius().is_some_and(|edge| rho >= edge);
    if !target.is_finite() || outside || !(member.omega > 0.0) || !member.m2.is_finite() {
        return out;
    }
    let r = GodelChart::new(member).event(target).r();
    let sigma_min = member.omega
        * base_coordinate(member, target.x, target.y)
            .norm_sqr()
            .sqrt();
    if !(sigma_min < 1.0) {
        return out;
    }
    let zp = target.z;
    if r == 0.0 {
        if zp == 0.0 {
            return out;
        }
        // The straight ray along z.
        out.extend(ray(
            member,
            target,
            (zp.signum(), 0.0),
            zp.abs(),
            0,
            Branch::Outbound,
        ));
    }
    let c_max = ((1.0 - sigma_min) * (1.0 + sigma_min)).sqrt();
    // Returning-only branches end where Λ = 0: |c| = c_esc (σ = 2Ω/m) for m² > 4Ω².
    let sin_esc = 2.0 * member.omega / member.m2.max(0.0).sqrt();
    let c_esc = if sin_esc < 1.0 {
        ((1.0 - sin_esc) * (1.0 + sin_esc)).sqrt()
    } else {
        0.0
    };
    let sign = zp.signum();
    for n in 0..=max_winding {
        for b in [Branch::Outbound, Branch::Inbound] {
            // On the axis the outbound branch of winding n is the inbound one of n − 1.
            if r == 0.0 && b == Branch::Outbound {
                continue;
            }
            if zp == 0.0 {
                if let Some(l) = lambda_at(member, r, (0.0, 1.0), n, b) {
                    out.extend(ray(member, target, (0.0, 1.0), l, n, b));
                }
                continue;
            }
            let c_lo = if n == 0 && b == Branch::Outbound {
                0.0
            } else {
                c_esc
            };
            if c_lo >= c_max {
                continue;
            }
            // Grid point i: |c| from c_lo to c_max, the last one (c_max, σ_min) exactly.
            let point = |i: usize| match i {
                GRID => (c_max, sigma_min),
                _ => {
                    let c = c_lo + (c_max - c_lo) * i as f64 / GRID as f64;
                    (c, ((1.0 - c) * (1.0 + c)).sqrt())
                }
            };
            let psi_of = |i: usize| match i {
                GRID => sigma_min.atan2(c_max),
                _ => {
                    let (c, s) = point(i);
                    s.atan2(c)
                }
            };
            let g = |psi: f64| {
                let (s, c) = psi.sin_cos();
                excess(member, r, zp, (c, s), n, b)
            };
            let mut found = |(c, s): (f64, f64)| {
                if let Some(l) = lambda_at(member, r, (c, s), n, b).filter(|l| l.is_finite()) {
                    out.extend(ray(member, target, (sign * c, s), l, n, b));
                }
            };
            let mut g0 = excess(member, r, zp, point(0), n, b);
            for i in 1..=GRID {
                let g1 = excess(member, r, zp, point(i), n, b);
                // A root exactly at c_max belongs to both branches: count it once.
                let at_join = i == GRID && b == Branch::Inbound && r > 0.0;
                if g1 == 0.0 && !at_join {
                    found(point(i));
                } else if g0 < 0.0 && g1 > 0.0 || g0 > 0.0 && g1 < 0.0 {
                    // ψ falls as |c| grows: the cell is [ψ_i, ψ_(i−1)].
                    let psi = refine_root(g, psi_of(i), psi_of(i - 1), g1, g0);
                    let (s, c) = psi.sin_cos();
                    found((c, s));
                }
                g0 = g1;
            }
        }
    }
    out.sort_by(|p, q| q.emission.t.total_cmp(&p.emission.t));
    out
}

/// All light rays from a source at rest at `source` (its x, y, z; t ignored) to `target` in
/// `member`: the axis case after mapping the source to the axis, mapped back. Empty where
/// no ray exists or the source lies outside the chart.
pub fn type_shadow_rays(
    member: GodelType,
    source: Event,
    target: Event,
    max_winding: u32,
) -> Vec<ShadowRay> {
    match source_frame(member, source) {
        Some(to) => rays_through(member, &to, target, max_winding),
        None => Vec::new(),
    }
}

/// The light rays of [`type_shadow_rays`] emitted at most `window` before `target`, found with
/// no more windings than the window can hold, at most `cap` (docs/physics.md, "Direct light
/// in the family"): on the source's axis a ray of winding n has travelled at least n
/// [`GodelType::shortest_loop_time`], t never falling along it, and the isometry to that axis
/// moves the target's time by δ. (On the sphere a ray from a source beyond |ζ_S| = 4Ω/μ²
/// winds about the image of the pole, and the cut's correction makes it emitted a period
/// 8πΩ/μ² earlier per loop: it travels longer, never shorter.)
pub fn type_shadow_rays_within(
    member: GodelType,
    source: Event,
    target: Event,
    window: f64,
    cap: u32,
) -> Vec<ShadowRay> {
    let Some(to) = source_frame(member, source) else {
        return Vec::new();
    };
    let shift = to.apply(target).t - target.t;
    let n = ((window + shift) / member.shortest_loop_time()).ceil();
    let windings = (n.clamp(0.0, f64::from(cap)) as u32).saturating_add(1);
    let mut rays = rays_through(member, &to, target, windings);
    rays.retain(|r| r.emission.t >= target.t - window);
    rays
}

/// The isometry that puts a source at rest at `source` (its t ignored) on the axis; `None`
/// outside the chart.
fn source_frame(member: GodelType, source: Event) -> Option<TypeIsometry> {
    TypeIsometry::to_origin(member, Event::new(0.0, source.x, source.y, source.z))
}

/// [`type_shadow_rays`] with the source's isometry `to` made.
fn rays_through(
    member: GodelType,
    to: &TypeIsometry,
    target: Event,
    max_winding: u32,
) -> Vec<ShadowRay> {
    let back = to.inverse();
    let moved = to.apply(target);
    let mut out: Vec<ShadowRay> = type_shadow_rays_from_axis(member, moved, max_winding)
        .into_iter()
        .filter_map(|r| {
            let mut ray = ShadowRay {
                emission: back.apply(r.emission),
                tangent: back.push(r.emission, r.tangent),
                ..r
            };
            if member.m2 < 0.0 {
                // The cut of the time shift: continue the closed form from the emission.
                let (end, _) =
                    TypeExactGeodesic::new(member, ray.emission, ray.tangent)?.at(ray.lambda);
                let period = 8.0 * PI * member.omega / -member.m2;
                ray.emission.t += ((target.t - end.t) / period).round() * period;
            }
            (ray.emission.is_finite() && ray.tangent.is_finite()).then_some(ray)
        })
        .collect();
    out.sort_by(|p, q| q.emission.t.total_cmp(&p.emission.t));
    out
}

/// The source's area distance squared, D² = dA/dΩ, of a light ray from a source at rest at
/// `source` in `member`, as [`crate::source_area_distance_sq`] defines it for Gödel and
/// computes it: in the frame where the source is on the axis (the isometry keeps the
/// metric, the affine parameter and static frames), J_χ = ∂_φ exactly (a Killing field) and
/// J_ψ by a central difference (h = 1e-5) of the closed form, D² = √det g(J_i, J_j)/sin ψ.
/// NaN where the ray leaves along ±z (sin ψ = 0) or is not from `source`.
pub fn type_source_area_distance_sq(member: GodelType, source: Event, ray: &ShadowRay) -> f64 {
    let Some(to) = TypeIsometry::to_origin(member, Event::new(0.0, source.x, source.y, source.z))
    else {
        return f64::NAN;
    };
    let k = to.push(ray.emission, ray.tangent);
    let chi = k.y.atan2(k.x);
    let psi = (k.x * k.x + k.y * k.y).sqrt().atan2(k.z);
    let end = |psi: f64| {
        let k = FourVector::new(1.0, psi.sin() * chi.cos(), psi.sin() * chi.sin(), psi.cos());
        TypeOriginGeodesic::new(member, k).map(|g| g.at(ray.lambda).0)
    };
    const H: f64 = 1e-5;
    let (Some(x), Some(xp), Some(xm)) = (end(psi), end(psi + H), end(psi - H)) else {
        return f64::NAN;
    };
    let j_psi = (xp - xm).to_array().map(|c| c / (2.0 * H));
    let j_chi = [0.0, -x.y, x.x, 0.0];
    let dot = |u: [f64; 4], v: [f64; 4]| {
        member.dot(x, FourVector::from_array(u), FourVector::from_array(v))
    };
    let det = dot(j_psi, j_psi) * dot(j_chi, j_chi) - dot(j_psi, j_chi).powi(2);
    det.max(0.0).sqrt() / psi.sin()
}
