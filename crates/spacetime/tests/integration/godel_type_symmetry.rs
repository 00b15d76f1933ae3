//! Symmetries of the Gödel-type family (`spacetime::godel_type_symmetry`, docs/physics.md
//! "The Gödel-type family"): the five Killing fields satisfy Killing's equation and close
//! under the bracket, the isometries preserve the metric, send their event to the origin and
//! invert, their flows are the Killing fields', and the Gödel member's are Gödel's.

use crate::common::{integrate_field, max_abs, Rng};
use spacetime::*;
use std::f64::consts::PI;

const OMEGA: f64 = 0.7;

/// Members m²/Ω² ∈ {−1, 0, 1, 2 (Gödel), 3.5, 4, 6} at Ω = 0.7, each with the largest proper
/// radius to test at (on the sphere, short of the pole at μρ = π where the chart ends).
pub fn members() -> Vec<(GodelType, f64)> {
    [-1.0, 0.0, 1.0, 2.0, 3.5, 4.0, 6.0]
        .iter()
        .map(|ratio| {
            let m = GodelType::new(ratio * OMEGA * OMEGA, OMEGA);
            let rho = match m.coordinate_radius() {
                Some(edge) => 0.75 * edge,
                None => 3.5,
            };
            (m, rho)
        })
        .collect()
}

/// ∂_λ ξ^μ by the fourth-order central difference (h = 1e-3), indexed `[lambda][mu]`.
fn jacobian(f: impl Fn(Event) -> FourVector, at: Event) -> [[f64; 4]; 4] {
    let h = 1e-3;
    let mut j = [[0.0; 4]; 4];
    for (l, row) in j.iter_mut().enumerate() {
        let mut e = [0.0; 4];
        e[l] = 1.0;
        let d = FourVector::from_array(e);
        let f1 = f(at.offset(d, h)).to_array();
        let fm1 = f(at.offset(d, -h)).to_array();
        let f2 = f(at.offset(d, 2.0 * h)).to_array();
        let fm2 = f(at.offset(d, -2.0 * h)).to_array();
        for m in 0..4 {
            row[m] = (8.0 * (f1[m] - fm1[m]) - (f2[m] - fm2[m])) / (12.0 * h);
        }
    }
    j
}

#[test]
fn killing_fields_of_every_member_satisfy_killings_equation() {
    // (L_ξ g)_μν = ξ^λ ∂_λ g_μν + g_λν ∂_μ ξ^λ + g_μλ ∂_ν ξ^λ, relative to its largest term.
    let mut rng = Rng::new(3401);
    let mut worst: f64 = 0.0;
    for (member, rho) in members() {
        for i in 0..80 {
            let at = if i == 0 {
                Event::default()
            } else {
                rng.event(rho)
            };
            let g = member.metric(at);
            let dg = member.metric_derivatives(at);
            for f in KillingField::ALL {
                let xi = killing_field(member, f, at).to_array();
                let dxi = jacobian(|e| killing_field(member, f, e), at);
                for mu in 0..4 {
                    for nu in 0..4 {
                        let (mut s, mut scale) = (0.0, 1.0f64);
                        for l in 0..4 {
                            for t in [
                                xi[l] * dg[l][mu][nu],
                                g[l][nu] * dxi[mu][l],
                                g[mu][l] * dxi[nu][l],
                            ] {
                                s += t;
                                scale = scale.max(t.abs());
                            }
                        }
                        let err = s.abs() / scale;
                        worst = worst.max(err);
                        assert!(err < 1e-9, "{f:?} {member:?} at {at:?}: {s:e}");
                    }
                }
            }
        }
    }
    eprintln!("family Killing's equation: worst relative residual {worst:e}");
}

#[test]
fn the_translations_are_the_cartesian_unit_vectors_on_the_axis() {
    for (member, _) in members() {
        let kx = killing_field(member, KillingField::Kx, Event::new(2.0, 0.0, 0.0, -1.0));
        let ky = killing_field(member, KillingField::Ky, Event::new(-3.0, 0.0, 0.0, 4.0));
        assert_eq!(kx, FourVector::new(0.0, 1.0, 0.0, 0.0));
        assert_eq!(ky, FourVector::new(0.0, 0.0, 1.0, 0.0));
        // Continuous there: the difference from ∂x, ∂y is O(ρ).
        let near = killing_field(member, KillingField::Ky, Event::new(0.0, 1e-7, -1e-7, 0.0));
        assert!(
            max_abs((near - ky).to_array()) < 1e-7,
            "{member:?}: {near:?}"
        );
    }
}

/// [X, Y]^μ = X^ν ∂_ν Y^μ − Y^ν ∂_ν X^μ.
fn bracket(member: GodelType, x: KillingField, y: KillingField, at: Event) -> FourVector {
    let f = |k: KillingField, e: Event| killing_field(member, k, e);
    let (xv, yv) = (f(x, at).to_array(), f(y, at).to_array());
    let (dx, dy) = (jacobian(|e| f(x, e), at), jacobian(|e| f(y, e), at));
    let mut out = [0.0; 4];
    for (mu, o) in out.iter_mut().enumerate() {
        for nu in 0..4 {
            *o += xv[nu] * dy[nu][mu] - yv[nu] * dx[nu][mu];
        }
    }
    FourVector::from_array(out)
}

/// [K_x, K_y] = 2Ω ∂t + m² ∂φ (Gödel: (√2/a) ∂t + (1/a²) ∂φ), [∂φ, K_x] = −K_y,
/// [∂φ, K_y] = K_x, ∂t and ∂z central.
#[test]
fn killing_fields_close_under_the_bracket() {
    use KillingField::*;
    let mut rng = Rng::new(3402);
    let mut worst: f64 = 0.0;
    for (member, rho) in members() {
        for _ in 0..30 {
            let at = rng.event(rho);
            let f = |k: KillingField| killing_field(member, k, at);
            let cases = [
                (Kx, Ky, (2.0 * member.omega) * f(T) + member.m2 * f(Phi)),
                (Phi, Kx, -f(Ky)),
                (Phi, Ky, f(Kx)),
                (T, Kx, FourVector::default()),
                (Z, Ky, FourVector::default()),
            ];
            for (x, y, want) in cases {
                let got = bracket(member, x, y, at);
                let scale = 1.0 + max_abs(f(Kx).to_array()).powi(2);
                let d = max_abs((got - want).to_array()) / scale;
                worst = worst.max(d);
                assert!(
                    d < 1e-9,
                    "{member:?} [{x:?},{y:?}] at {at:?}: {got:?} vs {want:?}"
                );
            }
        }
    }
    eprintln!("family commutators: worst deviation {worst:e}");
}

fn random_vector(rng: &mut Rng) -> FourVector {
    FourVector::new(
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
    )
}

/// Random isometries from events within `rho`: maps to the origin, some followed by a
/// rotation, and inverses of such maps.
fn random_isometries(rng: &mut Rng, member: GodelType, rho: f64, n: usize) -> Vec<TypeIsometry> {
    (0..n)
        .map(|i| {
            let t = TypeIsometry::to_origin(member, rng.event(rho)).unwrap();
            match i % 3 {
                0 => t,
                1 => t.then_rotate(rng.uniform(-4.0, 4.0)),
                _ => t.then_rotate(rng.uniform(-4.0, 4.0)).inverse(),
            }
        })
        .collect()
}

/// A random event whose image under `t` is within `rho` too: on the sphere the images of
/// points near the pole opposite the axis leave the chart, where the coordinates degenerate.
fn event_with_image(rng: &mut Rng, t: &TypeIsometry, rho: f64) -> Event {
    loop {
        let x = rng.event(rho);
        if t.apply(x).r() < rho {
            return x;
        }
    }
}

#[test]
fn the_map_to_the_origin_sends_its_event_there_and_the_inverse_undoes_it() {
    let mut rng = Rng::new(3403);
    let mut worst: f64 = 0.0;
    for (member, rho) in members() {
        for _ in 0..60 {
            let p0 = rng.event(rho);
            let t = TypeIsometry::to_origin(member, p0)
                .unwrap()
                .then_rotate(rng.uniform(-4.0, 4.0));
            let o = t.apply(p0);
            assert!(max_abs(o.to_array()) <= 1e-15, "{member:?}: T(P0) = {o:?}");
            let back = t.inverse().apply(Event::default());
            let d0 = max_abs((back - p0).to_array()) / (1.0 + max_abs(p0.to_array()));
            assert!(d0 < 1e-12, "{member:?}: T⁻¹(origin) = {back:?} vs {p0:?}");
            for _ in 0..5 {
                let x = event_with_image(&mut rng, &t, rho);
                let y = t.inverse().apply(t.apply(x));
                let d = max_abs((y - x).to_array()) / (1.0 + max_abs(x.to_array()));
                worst = worst.max(d).max(d0);
                assert!(d < 1e-12, "{member:?}: T⁻¹∘T({x:?}) = {y:?}");
            }
        }
    }
    eprintln!("family isometry round trips: worst relative error {worst:e}");
}

#[test]
fn apply_push_is_apply_and_push_and_the_differential_is_the_maps() {
    let mut rng = Rng::new(3404);
    let mut worst: f64 = 0.0;
    for (member, rho) in members() {
        let mut maps = random_isometries(&mut rng, member, rho, 30);
        maps.push(TypeIsometry::to_origin(member, Event::new(1.5, 0.0, 0.0, -0.4)).unwrap());
        maps.push(TypeIsometry::identity(member));
        for t in maps {
            let x = event_with_image(&mut rng, &t, rho);
            let v = random_vector(&mut rng);
            let (e, k) = t.apply_push(x, v);
            let (e1, k1) = (t.apply(x), t.push(x, v));
            assert!(max_abs((e - e1).to_array()) <= 1e-13 * (1.0 + max_abs(e1.to_array())));
            assert!(max_abs((k - k1).to_array()) <= 1e-13 * (1.0 + max_abs(k1.to_array())));
            let h = 1e-5;
            let fd = (1.0 / (2.0 * h)) * (t.apply(x.offset(v, h)) - t.apply(x.offset(v, -h)));
            let d = max_abs((k1 - FourVector::from_array(fd.to_array())).to_array())
                / (1.0 + max_abs(k1.to_array()));
            worst = worst.max(d);
            assert!(d < 1e-7, "{member:?} {t:?}: T_* v = {k1:?}, FD {fd:?}");
            // Static observers go to static observers.
            let dt = t.push(x, FourVector::new(1.0, 0.0, 0.0, 0.0));
            assert_eq!(dt, FourVector::new(1.0, 0.0, 0.0, 0.0));
        }
    }
    eprintln!("family differential vs finite differences: worst {worst:e}");
}

/// g(T_* u, T_* v) at T(x) = g(u, v) at x.
#[test]
fn isometries_of_every_member_preserve_the_metric() {
    let mut rng = Rng::new(3405);
    let mut worst: f64 = 0.0;
    for (member, rho) in members() {
        for t in random_isometries(&mut rng, member, rho, 100) {
            let x = event_with_image(&mut rng, &t, rho);
            let (u, v) = (random_vector(&mut rng), random_vector(&mut rng));
            let before = member.dot(x, u, v);
            let after = member.dot(t.apply(x), t.push(x, u), t.push(x, v));
            let g = member.metric(x);
            let (ua, va) = (u.to_array(), v.to_array());
            let scale = (0..16)
                .map(|i| (g[i / 4][i % 4] * ua[i / 4] * va[i % 4]).abs())
                .fold(0.0, f64::max);
            let d = (after - before).abs() / scale;
            worst = worst.max(d);
            assert!(d < 1e-11, "{member:?} {t:?} at {x:?}: {after} vs {before}");
        }
    }
    eprintln!("family metric preserved: worst relative error {worst:e}");
}

#[test]
fn finite_isometries_are_the_flows_of_the_killing_fields() {
    let mut rng = Rng::new(3406);
    let mut worst: f64 = 0.0;
    for (member, rho) in members() {
        for field in KillingField::ALL {
            for _ in 0..8 {
                let x = rng.event(0.6 * rho);
                let s = rng.uniform(-0.3, 0.3) * rho;
                let exact = TypeIsometry::flow(member, field, s).unwrap().apply(x);
                let numeric = integrate_field(|e| killing_field(member, field, e), x, s, 2000);
                let d = max_abs((exact - numeric).to_array()) / (1.0 + max_abs(x.to_array()));
                worst = worst.max(d);
                assert!(
                    d < 1e-9,
                    "{member:?} {field:?} {s} from {x:?}: {exact:?} vs {numeric:?}"
                );
            }
        }
    }
    eprintln!("family Killing flows vs RK4: worst relative difference {worst:e}");
}

/// Gödel's coordinates of the Gödel member's event: r = 2a sinh(ρ/2a), t, φ, z kept.
pub fn to_godel(a: f64, e: Event) -> Event {
    let rho = e.x.hypot(e.y);
    let s = if rho > 0.0 {
        2.0 * a * (rho / (2.0 * a)).sinh() / rho
    } else {
        1.0
    };
    Event::new(e.t, s * e.x, s * e.y, e.z)
}

/// The differential of [`to_godel`]: d(sX) = s dX + X s′(ρ) (X·dX)/ρ.
pub fn to_godel_vector(a: f64, e: Event, v: FourVector) -> FourVector {
    let rho = e.x.hypot(e.y);
    if rho == 0.0 {
        return v;
    }
    let h = rho / (2.0 * a);
    let s = h.sinh() / h;
    let ds = (h.cosh() - s) / rho; // d(sinh h/h)/dρ
    let radial = ds * (e.x * v.x + e.y * v.y) / rho;
    FourVector::new(v.t, s * v.x + radial * e.x, s * v.y + radial * e.y, v.z)
}

/// The Gödel member (m² = 1/a², Ω = 1/(√2 a)) carried to Gödel's r: its Killing fields are
/// `KillingField::at`, its maps to the origin are `Isometry::to_origin`.
#[test]
fn the_godel_members_symmetries_are_godels() {
    let mut rng = Rng::new(3407);
    let (mut wk, mut wi): (f64, f64) = (0.0, 0.0);
    for a in [1.0, 0.6] {
        let member = GodelType::new(1.0 / (a * a), 1.0 / (2f64.sqrt() * a));
        for _ in 0..50 {
            let x = rng.event(3.0 * a);
            for f in KillingField::ALL {
                let mine = to_godel_vector(a, x, killing_field(member, f, x));
                let theirs = f.at(a, to_godel(a, x));
                let d = max_abs((mine - theirs).to_array()) / (1.0 + max_abs(theirs.to_array()));
                wk = wk.max(d);
                assert!(d < 1e-12, "{f:?} a={a} at {x:?}: {mine:?} vs {theirs:?}");
            }
            let p0 = rng.event(3.0 * a);
            let alpha = rng.uniform(-4.0, 4.0);
            let mine = TypeIsometry::to_origin(member, p0)
                .unwrap()
                .then_rotate(alpha);
            let theirs = Isometry::to_origin(a, to_godel(a, p0)).then_rotate(alpha);
            let v = random_vector(&mut rng);
            let (e1, k1) = mine.apply_push(x, v);
            let (e1, k1) = (to_godel(a, e1), to_godel_vector(a, e1, k1));
            let (e2, k2) = theirs.apply_push(to_godel(a, x), to_godel_vector(a, x, v));
            let d = (max_abs((e1 - e2).to_array()) / (1.0 + max_abs(e2.to_array())))
                .max(max_abs((k1 - k2).to_array()) / (1.0 + max_abs(k2.to_array())));
            wi = wi.max(d);
            assert!(d < 1e-11, "a={a}: {e1:?} {k1:?} vs {e2:?} {k2:?}");
        }
    }
    eprintln!("Gödel member vs Gödel: Killing fields {wk:e}, isometries {wi:e}");
}

/// On the sphere `to_origin` refuses events at and beyond the pole opposite the axis, and the
/// time shift jumps by the flux 8πΩ/μ² across its cut (1 − k ζ̄0 ζ real and negative).
#[test]
fn on_the_sphere_the_chart_ends_at_the_pole_and_the_time_shift_has_a_cut() {
    let member = GodelType::new(-OMEGA * OMEGA, OMEGA);
    let mu = OMEGA;
    assert!(TypeIsometry::to_origin(member, Event::new(0.0, PI / mu, 0.0, 0.0)).is_none());
    assert!(TypeIsometry::to_origin(member, Event::new(0.0, 0.0, -4.0 / mu, 0.0)).is_none());
    let t = TypeIsometry::to_origin(member, Event::new(0.0, 2.0 / mu, 0.0, 0.0)).unwrap();
    // The cut: points on the negative x axis beyond the one sent to the pole, where
    // tan(μρ/2) tan(μρ0/2) = 1, i.e. ρ = (π − 2)/μ.
    let rho = ((PI - 2.0) + 0.4) / mu;
    let above = t.apply(Event::new(0.0, -rho, 1e-9, 0.0));
    let below = t.apply(Event::new(0.0, -rho, -1e-9, 0.0));
    let jump = (above.t - below.t).abs();
    let flux = 8.0 * PI * OMEGA / (mu * mu);
    assert!((jump - flux).abs() < 1e-6 * flux, "jump {jump} vs {flux}");
    let d = (above.x - below.x).hypot(above.y - below.y);
    assert!(d < 1e-6, "the image is continuous: {above:?} vs {below:?}");
}
