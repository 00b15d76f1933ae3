//! The far probes' rate bound (`render::target::FAR_RATE_MARGIN`, docs/physics.md "The
//! intersection search"): along rays that enter a local ball, a far probe's distance is never
//! more than the rate bound allows for the stretch of ray between it and the entry (or the
//! exit), so a span between two far probes that holds a crossing is never excluded.

use crate::common;
use render::target::{Target, FAR_RATE_MARGIN};
use spacetime::{ExactGeodesic, GeodesicState, Spacetime};

/// Balls at rest and falling at up to 0.85 c, radii up to a/2, up to 1.8a from the axis, where
/// the far margin is used (speed factor s = γ(1 + v) ≤ 3.5 and s·R ≤ a); rays through random
/// points inside, in random directions. The entry and the exit are found by walking out from
/// the point with the exact rest-frame distance; then at every far probe up to 8a/(E·s) of
/// ray parameter beyond them, the probe's distance f must satisfy f ≤ ρ·E·s·gap (E·s: the
/// photon's largest rest-frame energy; gap: the parameter to the entry or from the exit) with
/// ρ = FAR_RATE_MARGIN/1.25, a quarter of room kept. Largest ρ found here: 0.95 at rest
/// (head-on, where the far slack is 1.1), 0.83 falling (over 6,000 balls once: 1.04 and
/// 0.95). Fails with the margin cut to 1.15. (Beyond s·R = a the
/// first-order estimate can be far off: one ball at 0.78 c with R = 0.48a, out of 6,000
/// tried, had a far probe at ρ = 1.89 next to its surface; such balls keep the near margin.)
#[test]
fn far_probes_never_outrun_their_rate_toward_an_entry() {
    let mut rng = common::Cases(7);
    let (mut entries, mut samples, mut worst) = (0usize, 0usize, [0.0f64; 2]);
    for case in 0..2500 {
        let (a, m, speed, radius, target) =
            common::random_ball(&mut rng, case % 4 == 0, 0.85, 30.0);
        let Target::LocalSphere { worldline, .. } = &target else {
            unreachable!()
        };
        let p = worldline.at(&m, 0.0).unwrap();
        let (off, d) = (0.95 * radius * rng.unit(), rng.direction());
        let x0 = p.event.offset(p.frame.spatial(d), off);
        let n = rng.direction();
        let k = m.static_frame(x0).vector([-1.0, n[0], n[1], n[2]]);
        let ray = ExactGeodesic::new(a, x0, k).unwrap();
        let (energy, s) = (m.lower(x0, k).t.abs(), worldline.speed_factor());
        if s * radius > a {
            continue; // the near margin's domain
        }
        let h = 0.002 * a / (energy * s);
        // The entry (λ < 0) and the exit (λ > 0): the last points inside, walking out from
        // λ = 0 with each match seeded by the previous one.
        let mut edge = [f64::NAN; 2];
        for (side, dir) in [(0, -1i64), (1, 1)] {
            let mut seed = p.tau;
            for i in 0..=2000 {
                let l = (dir * i) as f64 * h;
                let Some(lp) = worldline
                    .localize(&m, ray.at(l).0, seed, f64::INFINITY)
                    .and_then(|l| l.near())
                else {
                    break;
                };
                seed = lp.at.tau;
                if lp.xi.iter().map(|c| c * c).sum::<f64>().sqrt() > radius {
                    edge[side] = l;
                    break;
                }
            }
        }
        let [entry, exit] = edge;
        if !(entry.is_finite() && exit.is_finite()) {
            continue;
        }
        entries += 1;
        for i in -4000..=4000 {
            let l = i as f64 * h;
            if l > entry && l < exit {
                continue;
            }
            let (x, kx) = ray.at(l);
            let probe = target.probe(
                &m,
                &GeodesicState {
                    x,
                    p: m.lower(x, kx),
                },
                f64::NAN,
            );
            if probe.xi[0].is_finite() || !probe.f.is_finite() {
                continue; // near (the near margin), or no match
            }
            samples += 1;
            let gap = if l <= entry { entry - l } else { l - exit };
            let rho = probe.f / (energy * s * gap);
            let w = &mut worst[usize::from(speed > 0.0)];
            *w = w.max(rho);
            assert!(
                1.25 * rho <= FAR_RATE_MARGIN,
                "case {case} (v = {speed:.2}, R = {radius:.3}, a = {a:.2}): a far probe \
                 {gap:.4} before the ball has f = {:.4}, {rho:.3}·E·s·gap",
                probe.f
            );
        }
    }
    eprintln!("{entries} entries, {samples} far probes, largest f/(E·s·gap) (at rest, falling) {worst:.3?}");
    // Not vacuous: many rays enter, and the bound is not loose by far.
    assert!(
        entries > 1000 && samples > 1_000_000,
        "{entries} entries, {samples} probes"
    );
    assert!(worst.iter().all(|&w| w > 0.6), "largest {worst:?}");
}
