use render::intersect::Intersector;
use render::lighting::{LightSource, Lighting};
use render::target::Target;
use render::tracer::{TraceOptions, Tracer};
use scene::Scene;
use spacetime::{source_area_distance_sq, ExactGeodesic, Spacetime};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let text = std::fs::read_to_string(&args[1]).unwrap();
    let mut scene = Scene::from_str(&text, &args[1]).unwrap();
    if args.len() >= 5 {
        scene.camera = scene.camera.with_size(args[3].parse().unwrap(), args[4].parse().unwrap());
    }
    let idx: u32 = args[2].parse().unwrap();
    let cam = scene.sample_camera();
    let (col, row) = (idx % cam.width(), idx / cam.width());
    let m = scene.metric;
    let obs = scene.observer;
    let frame = m.observer_frame(obs.event, obs.velocity);
    let targets: Vec<Target> = scene
        .objects
        .iter()
        .map(|o| Target::new(m, o, -100.0, 10.0).unwrap())
        .collect();
    let objects = Intersector { metric: m, targets };
    let tracer = Tracer::new(
        objects,
        obs.event,
        frame,
        TraceOptions {
            max_past: scene.trace.max_past,
            tolerance: 1e-11,
            max_steps: 100000,
            exact: true,
        },
    );
    let mut scratch = tracer.scratch();
    let dir = obs.pixel_direction(&cam, col, row).unwrap();
    let t = tracer.trace(dir, &mut scratch);
    let hit = t.hit.unwrap();
    let a = m.godel_a().unwrap();
    let light = LightSource::from_scene(&scene.lights[0]);
    let lighting = Lighting::new(vec![light], scene.trace.max_past);
    let x = hit.state.x;
    let view = m.raise(x, hit.state.p);
    let mut sum = 0.0;
    for ray in lighting.connecting_rays(a, &light, x) {
        let geo = ExactGeodesic::new(a, ray.emission, ray.tangent).unwrap();
        let (_, k_end) = geo.at(ray.lambda);
        let inc = tracer.objects.targets[hit.target]
            .incidence(&m, x, hit.tau, view, k_end)
            .unwrap();
        let d2 = source_area_distance_sq(a, light.position, &ray);
        let e = light.power * inc.energy * inc.energy * inc.cos / (4.0 * std::f64::consts::PI * d2);
        if inc.cos > 0.0 {
            sum += e;
        }
        // The least distance of this ray from each object, sampled finely.
        let mut fmin = vec![f64::INFINITY; tracer.objects.targets.len()];
        let steps = 20000;
        for s in 0..steps {
            let l = ray.lambda * (s as f64 + 0.5) / steps as f64;
            let (x, k) = geo.at(l);
            let st = spacetime::GeodesicState { x, p: m.lower(x, k) };
            for (i, t) in tracer.objects.targets.iter().enumerate() {
                if i == hit.target && l > ray.lambda * 0.95 { continue; }
                fmin[i] = fmin[i].min(t.probe(&m, &st, f64::NAN).f);
            }
        }
        if ray.winding == 5 && ray.branch == spacetime::Branch::Inbound {
            println!("  ray 5in: emission {:?} tangent {:?} lambda {}", ray.emission, ray.tangent, ray.lambda);
        }
        println!(
            "n {} {:?} t_em {:.5} cos {:.6} energy {:.8} d2 {:.6} E {:.6e} fmin {:?}",
            ray.winding, ray.branch, ray.emission.t, inc.cos, inc.energy, d2, e, fmin.iter().map(|v| format!("{v:.2e}")).collect::<Vec<_>>()
        );
    }
    let mut out = [0f32];
    lighting.illuminate(&tracer.objects, Some(&hit), &mut scratch.probes, &mut out);
    println!("x = {x:?}; unoccluded sum {sum:.6}; illuminate {}", out[0]);
}
