//! Chord exclusion (`render::chord`, docs/physics.md "The intersection search"): a ray's
//! rest-frame path near a local ball stays within the bound of its chords, records and
//! direct light are the same, bit for bit, with the chord exclusion as without it, and the
//! search with every exclusion finds no hit later than a dense scan of the ray.

use crate::common::{self, tracer};
use render::chord;
use render::lighting::{LightSource, Lighting};
use render::target::Target;
use render::worldline::Located;
use scene::Scene;
use spacetime::{ExactGeodesic, Spacetime};

/// Balls at rest, falling slowly (up to 0.1 c) and falling at up to 0.8 c (the fastest the
/// test is used for), of radii up to a/2, at up to 1.8a from the axis; rays through random
/// points within 0.45a of a centre, in random directions. Wherever both ends of a span lie
/// near the ball and `chord::stray` gives a bound, every sampled point of the path between
/// them lies within half that bound of the chord (at the same fraction of the span): the
/// bound's margin of two. The bound takes the photon energy the renderer takes
/// (`chord::photon_energy`: a falling ball's from its ends' |p·u|, computed here as a probe
/// does). Fails with the bend at rest cut from 3.25 to 3, the falling ball's constant term
/// from 0.75 to 0 (slow balls: 0.77 of the bound), the boost term from s⁴ to s³, or
/// `chord::LOCAL_ENERGY_MARGIN` from 2 to 1. Prints (`--nocapture`) the table of
/// docs/physics.md, "Chord exclusion": the bend K = 8·(largest distance from the chord over
/// 4f(1 − f))/h² that spans need, in units of (E·s)²/a, by speed (bins of 0.05 c) and by ρ,
/// the larger end's distance from the centre plus 0.05a (bins of 0.05a), with the largest
/// share of the bound by speed.
#[test]
fn a_rays_rest_frame_path_stays_within_its_chord_bound() {
    // Bins: at rest, then falling at [0.05k, 0.05(k + 1)) c; ρ from 0.05a to 0.55a.
    const SPEEDS: usize = 17;
    const RHOS: usize = 10;
    let mut rng = common::Cases(33);
    let (mut spans, mut worst) = (0usize, [0.0f64; 2]);
    let (mut need, mut share) = ([[0.0f64; RHOS]; SPEEDS], [0.0f64; SPEEDS]);
    for case in 0..4000 {
        let fastest = if case % 4 == 1 { 0.1 } else { 0.8 };
        let (a, m, speed, radius, target) =
            common::random_ball(&mut rng, case % 4 == 0, fastest, 20.0);
        let Target::LocalSphere { worldline, .. } = &target else {
            unreachable!()
        };
        // A point of the centre's rest space, within 0.45a of it, and a ray through it.
        let p = worldline.at(&m, 0.0).unwrap();
        let (off, d) = (0.45 * a * rng.unit(), rng.direction());
        let x0 = p.event.offset(p.frame.spatial(d), off);
        let n = rng.direction();
        let k = m.static_frame(x0).vector([-1.0, n[0], n[1], n[2]]);
        let ray = ExactGeodesic::new(a, x0, k).unwrap();
        let (energy, s) = (m.lower(x0, k).t.abs(), worldline.speed_factor());
        // Sample the path, each match seeded by the previous one as the search does: the
        // rest-frame coordinates, and whether the search's probe there is near (only near
        // probes carry them; between two, the path has them all the same).
        let h = 0.004 * a / (energy * s);
        let far = 0.25 * a + radius;
        let mut seed = f64::NAN;
        let xi: Vec<Option<([f64; 3], bool, f64)>> = (-300..=300)
            .map(|i| {
                let (x, k) = ray.at(i as f64 * h);
                let guess = if seed.is_finite() {
                    seed
                } else {
                    worldline.tau_guess(x.t)
                };
                let near = matches!(
                    worldline.localize(&m, x, guess, far),
                    Some(Located::Near(_))
                );
                let lp = worldline
                    .localize(&m, x, guess, f64::INFINITY)
                    .and_then(|l| l.near());
                seed = lp.map_or(f64::NAN, |l| l.at.tau);
                // The probe's energy there: |p·u| (`Probe::energy`).
                lp.map(|l| (l.xi, near, l.at.frame.e[0].contract(m.lower(x, k)).abs()))
            })
            .collect();
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let bin = if speed == 0.0 {
            0
        } else {
            (1 + (speed * 20.0) as usize).min(SPEEDS - 1)
        };
        let unit = (energy * s).powi(2) / a;
        for len in [2, 4, 8, 16, 32, 64, 128, 256] {
            let span = len as f64 * h;
            for i in (0..xi.len().saturating_sub(len)).step_by(3) {
                let (Some((xa, true, ea)), Some((xb, true, eb))) = (xi[i], xi[i + len]) else {
                    continue;
                };
                let ends = norm(xa).max(norm(xb));
                // The fraction f of the span at step j, and the path's distance there from
                // the chord at the same fraction (None where no match).
                let at = |j: usize| {
                    let f = j as f64 / len as f64;
                    let (x, _, _) = xi[i + j]?;
                    Some((
                        f,
                        norm([0, 1, 2].map(|c| x[c] - (xa[c] + f * (xb[c] - xa[c])))),
                    ))
                };
                let bend = (1..len).try_fold(0.0f64, |k, j| {
                    let (f, dev) = at(j)?;
                    Some(k.max(2.0 * dev / (f * (1.0 - f) * span * span)))
                });
                // Spans too long for any bound near these (stray ≤ 0.05a at K = 0.2) say
                // nothing the search uses.
                let rho = (ends / (0.05 * a)) as usize;
                if let Some(k) = bend.filter(|_| rho < RHOS && 0.2 * unit * span * span <= 0.4 * a)
                {
                    need[bin][rho] = need[bin][rho].max(k / unit);
                }
                let e = chord::photon_energy(speed == 0.0, s, energy, (ea, eb));
                let Some(stray) = chord::stray(a, speed == 0.0, s, e, ends, span) else {
                    continue;
                };
                for j in 1..len {
                    let Some((_, dev)) = at(j) else {
                        panic!("case {case}: no match between two near ends");
                    };
                    let w = &mut worst[usize::from(speed > 0.0)];
                    *w = w.max(dev / stray);
                    share[bin] = share[bin].max(dev / stray);
                    assert!(
                        dev <= 0.5 * stray,
                        "case {case} (v = {speed:.2}, R = {radius:.3}, a = {a:.2}): the path \
                         strays {dev:e} from a chord of {len} steps, more than half its bound \
                         {stray:e}"
                    );
                }
                spans += 1;
            }
        }
    }
    eprintln!("{spans} spans, largest stray (at rest, falling) {worst:.3?} of the bound");
    eprint!("the bend spans need, in (E s)²/a; ρ/a <");
    for r in 0..RHOS {
        eprint!(" {:>5.2}", 0.05 * (r + 2) as f64);
    }
    eprintln!("  | largest share of the bound");
    for (bin, row) in need.iter().enumerate() {
        match bin {
            0 => eprint!("{:>41}", "at rest"),
            _ => eprint!(
                "{:>41}",
                format!("{:.2}–{:.2} c", 0.05 * (bin - 1) as f64, 0.05 * bin as f64)
            ),
        }
        for k in row {
            eprint!(" {k:>5.2}");
        }
        eprintln!("  | {:.2}", share[bin]);
    }
    // Not vacuous: many spans checked, and the bound not loose by orders of magnitude.
    assert!(spans > 100_000, "only {spans} spans checked");
    for w in worst {
        assert!(
            w > 0.05,
            "the bound is {:.0} times the largest stray",
            1.0 / w
        );
    }
}

/// Every pixel's record of the reference scene (a ball falling at 0.7 c), both tracers, and
/// of floor-grid (a ball at rest over a lit floor), with the direct light at every hit,
/// are the same, bit for bit, with the chord exclusion as without it.
#[test]
fn records_and_light_are_the_same_with_and_without_chords() {
    for (name, method, w, h) in [
        ("reference.toml", "exact", 176, 20),
        ("reference.toml", "numeric", 88, 10),
        ("floor-grid.toml", "exact", 64, 36),
    ] {
        let sc = common::scene_file(name, method, w, h);
        let (with, without) = (tracer(&sc), tracer(&sc).without_chords());
        let sources: Vec<LightSource> = sc.lights.iter().map(LightSource::from_scene).collect();
        let lighting = Lighting::new(sources, sc.trace.max_past);
        let (mut s1, mut s2) = (with.scratch(), without.scratch());
        let (mut o1, mut o2) = (vec![0.0f32; sc.lights.len()], vec![0.0f32; sc.lights.len()]);
        let mut lit = 0;
        for row in 0..sc.camera.height() {
            for col in 0..sc.camera.width() {
                let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
                let (t1, t2) = (with.trace(n, &mut s1), without.trace(n, &mut s2));
                let place = format!("{name} {method} pixel ({col}, {row})");
                assert_eq!(
                    format!("{:?}", t1.record),
                    format!("{:?}", t2.record),
                    "{place}"
                );
                let (Some(h1), Some(h2)) = (t1.hit, t2.hit) else {
                    continue;
                };
                lighting.illuminate(&with.objects, Some(&h1), &mut s1.probes, &mut o1);
                lighting.illuminate(&without.objects, Some(&h2), &mut s2.probes, &mut o2);
                assert_eq!(format!("{o1:?}"), format!("{o2:?}"), "{place}");
                lit += usize::from(o1.iter().any(|&l| l > 0.0));
            }
        }
        assert!(
            sc.lights.is_empty() || lit > 100,
            "{name}: only {lit} lit hits"
        );
    }
}

/// A pixel's ray scanned densely (steps of 0.002 in λ, a hundredth of the ball's radius at
/// the photon's energy, seeds as the search's): the first λ where the ray point lies inside
/// the falling ball, the second-order |ξ| ≤ R, before `until` (None: none).
fn first_inside(sc: &Scene, target: &Target, col: u32, row: u32, until: f64) -> Option<f64> {
    let Target::LocalSphere { radius, worldline } = target else {
        unreachable!()
    };
    let m = sc.metric;
    let frame = m.observer_frame(sc.observer.event, sc.observer.velocity);
    let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
    let k = frame.vector([-1.0, n[0], n[1], n[2]]);
    let a = m.godel_a().unwrap();
    let ray = ExactGeodesic::new(a, sc.observer.event, k).unwrap();
    let far = 0.25 * a + radius;
    let mut seed = f64::NAN;
    let mut l = 0.0;
    while l < until {
        let x = ray.at(l).0;
        if x.t < sc.observer.event.t - sc.trace.max_past {
            return None;
        }
        // The previous match and the point of equal coordinate time, the nearer kept.
        let mut best = f64::INFINITY;
        for s in [seed, worldline.tau_guess(x.t)] {
            if let Some(Located::Near(lp)) = worldline.localize(&m, x, s, far) {
                let d = (lp.xi[0].powi(2) + lp.xi[1].powi(2) + lp.xi[2].powi(2)).sqrt();
                if d < best {
                    (best, seed) = (d, lp.at.tau);
                }
            }
        }
        if best == f64::INFINITY {
            seed = f64::NAN;
        }
        if best <= *radius {
            return Some(l);
        }
        l += 0.002;
    }
    None
}

/// The reference scene (a ball falling at 0.7 c) and a ball falling at 0.8 c, the fastest the
/// chord exclusion is used for: wherever a dense scan finds the ray inside the ball, the
/// exact tracer has hit it no later (0.01 in λ: the scan's resolution and the refinement's).
/// So no exclusion (rate, chord, loop windows) drops a span the ray enters the ball in.
/// Fails with the rate bound's margin cut from 2 to 0.3 (on the faster ball). (A chord that
/// excluded every span of two outside ends near the ball went unseen here: a span short
/// enough for the chord test to apply is crossed only by the shallowest grazes.)
#[test]
fn the_search_finds_every_entry_a_dense_scan_finds() {
    let fast = common::scene(
        "name = \"fast\"\n[spacetime]\nmetric = \"godel\"\na = 1.0\n\
         [observer]\ntime = 0.0\nposition = { r = 0.0, phi = 0.0, z = 0.0 }\n\
         forward = [-1, 0, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"panorama\"\nh_fov_deg = 220.0\nv_fov_deg = 25.0\nwidth = 88\nheight = 10\n\
         [trace]\nmethod = \"exact\"\nmax_past = 30\n\
         [[object]]\nname = \"falling\"\nradius = 0.15\n\
         motion = { kind = \"geodesic\", time = 0.0, position = { x = -1.0, y = 0.3, z = 0.0 }, speed = 0.8, direction = [1, 0, 0.2] }\n",
    );
    for sc in [common::reference_scene("exact", 88, 10), fast] {
        let tr = tracer(&sc);
        let mut scratch = tr.scratch();
        let mut hits = 0;
        for row in 0..sc.camera.height() {
            for col in 0..sc.camera.width() {
                let n = sc.observer.pixel_direction(&sc.camera, col, row).unwrap();
                let rec = tr.trace(n, &mut scratch).record;
                let until = if rec.object >= 0 {
                    hits += 1;
                    rec.lambda as f64 - 0.01
                } else {
                    40.0
                };
                let entry = first_inside(&sc, &tr.objects.targets[0], col, row, until);
                assert!(
                    entry.is_none(),
                    "{}: pixel ({col}, {row}) is inside the ball at λ {entry:?}, the tracer's \
                     record: object {} at λ {}",
                    sc.name,
                    rec.object,
                    rec.lambda
                );
            }
        }
        assert!(hits > 20, "{}: only {hits} hits", sc.name);
    }
}
