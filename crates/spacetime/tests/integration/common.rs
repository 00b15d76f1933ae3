//! Shared helpers for the spacetime tests: a tiny deterministic random generator,
//! random events/directions (no external crates needed), the largest component, and a
//! light bundle's area distance by brute force.

use spacetime::{
    trace, Event, FourVector, Geodesic, GeodesicKind, Metric, ShadowRay, Spacetime, TraceLimits,
};

/// xorshift64*: deterministic, good enough to spread test points.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }
    /// A random event with r < r_max.
    pub fn event(&mut self, r_max: f64) -> Event {
        let r = self.uniform(0.0, r_max);
        let phi = self.uniform(-std::f64::consts::PI, std::f64::consts::PI);
        Event::new(
            self.uniform(-5.0, 5.0),
            r * phi.cos(),
            r * phi.sin(),
            self.uniform(-3.0, 3.0),
        )
    }
    /// A random unit vector.
    pub fn direction(&mut self) -> [f64; 3] {
        loop {
            let v = [
                self.uniform(-1.0, 1.0),
                self.uniform(-1.0, 1.0),
                self.uniform(-1.0, 1.0),
            ];
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n > 0.1 && n <= 1.0 {
                return [v[0] / n, v[1] / n, v[2] / n];
            }
        }
    }
}

/// The largest absolute component.
pub fn max_abs(v: [f64; 4]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Integrates dX/ds = ξ(X) from `x` over `s` with classical RK4 in `steps` steps.
pub fn integrate_field(
    field: impl Fn(Event) -> FourVector,
    x: Event,
    s: f64,
    steps: usize,
) -> Event {
    let h = s / steps as f64;
    let f = |e: Event| field(e).to_array();
    let add = |e: Event, k: [f64; 4], c: f64| {
        let v = e.to_array();
        Event::from_array(std::array::from_fn(|i| v[i] + c * k[i]))
    };
    let mut e = x;
    for _ in 0..steps {
        let k1 = f(e);
        let k2 = f(add(e, k1, 0.5 * h));
        let k3 = f(add(e, k2, 0.5 * h));
        let k4 = f(add(e, k3, h));
        let k: [f64; 4] =
            std::array::from_fn(|i| (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]) / 6.0);
        e = add(e, k, h);
    }
    e
}

/// D² = dA/dΩ by brute force: rays launched numerically from the source's static frame in
/// directions (ψ ± h, χ) and (ψ, χ ± h) around the ray's, their spread after the ray's
/// affine length, and the area √det g(J_i, J_j) per solid angle sin ψ dψ dχ (Gödel's
/// universe or a Gödel-type member).
pub fn numeric_area_distance_sq(m: Metric, r: &ShadowRay) -> f64 {
    let frame = m.static_frame(r.emission);
    let n: Vec<f64> = (1..4)
        .map(|i| m.dot(r.emission, frame.e[i], r.tangent))
        .collect();
    let (psi, chi) = (n[2].clamp(-1.0, 1.0).acos(), n[1].atan2(n[0]));
    let end = |psi: f64, chi: f64| {
        let k = frame.vector([1.0, psi.sin() * chi.cos(), psi.sin() * chi.sin(), psi.cos()]);
        let g = Geodesic::from_tangent(&m, GeodesicKind::Null, r.emission, k);
        let limits = TraceLimits {
            max_affine: r.lambda,
            ..Default::default()
        };
        trace(m, &g, &limits).end.x
    };
    let h = 1e-4;
    let d = |p: Event, q: Event| (p - q).to_array().map(|c| c / (2.0 * h));
    let j1 = d(end(psi + h, chi), end(psi - h, chi));
    let j2 = d(end(psi, chi + h), end(psi, chi - h));
    let x = end(psi, chi);
    let dot =
        |u: [f64; 4], v: [f64; 4]| m.dot(x, FourVector::from_array(u), FourVector::from_array(v));
    (dot(j1, j1) * dot(j2, j2) - dot(j1, j2).powi(2)).sqrt() / psi.sin()
}
