use render::intersect::Intersector;
use render::lighting::{LightSource, Lighting};
use render::target::Target;
use render::tracer::{TraceOptions, Tracer};
use scene::Scene;
use spacetime::{source_area_distance_sq, ExactGeodesic, Spacetime};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let text = std::fs::read_to_string(&args[1]).unwrap();
    let scene = Scene::from_str(&text, &args[1]).unwrap();
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
        let mut single = [0f32];
        let one = Lighting::new(vec![light], scene.trace.max_past);
        let _ = &one;
        println!(
            "n {} {:?} t_em {:.5} cos {:.6} energy {:.8} d2 {:.6} E {:.6e}",
            ray.winding, ray.branch, ray.emission.t, inc.cos, inc.energy, d2, e
        );
    }
    let mut out = [0f32];
    lighting.illuminate(&tracer.objects, Some(&hit), &mut scratch.probes, &mut out);
    println!("x = {x:?}; unoccluded sum {sum:.6}; illuminate {}", out[0]);
}
