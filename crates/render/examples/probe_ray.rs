//! Debug aid: along one pixel's ray, prints the exact rest-frame distance to object 0 and
//! the first-order far estimate, with the global rate bound.
//! `cargo run -p render --example probe_ray -- SCENE COL ROW LAMBDA0 LAMBDA1`

use render::target::Target;
use render::worldline::Located;
use spacetime::*;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let scene = scene::Scene::from_file(&a[0]).unwrap();
    let (col, row): (u32, u32) = (a[1].parse().unwrap(), a[2].parse().unwrap());
    let (l0, l1): (f64, f64) = (a[3].parse().unwrap(), a[4].parse().unwrap());
    let m = scene.metric;
    let obs = scene.observer;
    let frame = m.observer_frame(obs.event, obs.velocity);
    let n = obs.pixel_direction(&scene.camera, col, row).unwrap();
    let g = Geodesic::from_tangent(
        &m,
        GeodesicKind::Null,
        obs.event,
        frame.vector([-1.0, n[0], n[1], n[2]]),
    );
    let tr = trace(
        m,
        &g,
        &TraceLimits {
            max_affine: l1 + 0.01,
            ..Default::default()
        },
    );
    let t = Target::new(m, &scene.objects[0], -31.0, 1.0).unwrap();
    let Target::LocalSphere { radius, worldline } = &t else {
        panic!()
    };
    for i in 0..=40 {
        let l = l0 + (l1 - l0) * i as f64 / 40.0;
        let s = tr.state_at(l);
        let exact = worldline
            .localize(&m, s.x, worldline.tau_guess(s.x.t), f64::INFINITY)
            .and_then(Located::near)
            .unwrap();
        let d = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt() - radius;
        let far = match worldline
            .localize(&m, s.x, worldline.tau_guess(s.x.t), 0.0)
            .unwrap()
        {
            Located::Far(distance) => distance - radius,
            Located::Near(lp) => d(lp.xi),
        };
        let p = t.probe(&m, &s, f64::NAN);
        println!(
            "λ {l:.4} t {:.3} exact f {:.5} far f {:.5} probe f {:.5} rate {:.3}",
            s.x.t,
            d(exact.xi),
            far,
            p.f,
            p.rate
        );
    }
}
