//! Holding the GPU kernel to the CPU exact tracer (docs/physics.md, "The GPU kernel"): both
//! trace the same scene, and the records are compared channel by channel with the
//! tolerances single precision allows.

use datafile::{DataFile, PixelRecord, RayStatus};
use gpu::KERNEL;
use render::driver::{render, NoProgress};
use scene::{Scene, TraceMethod};

/// How a GPU render agrees with the CPU exact tracer's.
#[derive(Debug)]
pub struct Agreement {
    pub name: String,
    /// Samples either tracer sees an object in.
    pub seen: usize,
    /// Of those, the fraction with the same object and status, and how many differ.
    pub same: f64,
    pub differ: usize,
    /// |Δg|/g over samples both see the same object in: median and 99.9th percentile.
    pub g_median: f64,
    pub g_p999: f64,
    /// |Δt_emit|/(1 + |t_emit|): 99.9th percentile.
    pub t_p999: f64,
    /// The polarization channels pol_x, pol_y, pol_z (unit vectors): the largest difference
    /// of a component per sample, over samples both see the same object in: 99.9th
    /// percentile.
    pub pol_p999: f64,
    /// Samples with light on either side (per light, pooled) whose hit events agree to
    /// [`SAME_EVENT`], and the fraction of them within 1e-3 relative (NaN on both sides
    /// agrees); and the lit samples left out because single precision moved their hit
    /// event further (a ray grazing a plane after many loops).
    pub lit: usize,
    pub light_within: f64,
    pub lit_moved: usize,
    /// Whether every sample has the same status on both.
    pub statuses_equal: bool,
    /// Samples marked `work limit` by the GPU and by the CPU: the GPU has no bound the CPU
    /// has not (docs/physics.md, "Bounds of a GPU"), so never more.
    pub work_limit: [usize; 2],
}

/// The tolerances (docs/physics.md, "The GPU kernel"). One sample may differ however
/// few are seen: on a frame that sees fewer than 200, 99.5 % would allow none.
pub const SAME: f64 = 0.995;
pub const G_MEDIAN: f64 = 1e-4;
pub const G_P999: f64 = 1e-3;
pub const T_P999: f64 = 1e-4;
pub const POL_P999: f64 = 1e-4;
pub const LIGHT_WITHIN: f64 = 0.999;
/// Hit events closer than this (coordinate distance, in units of a) count as one point for the
/// light comparison: light is compared where both lit the same point.
pub const SAME_EVENT: f32 = 1e-5;

impl Agreement {
    /// Whether every tolerance holds.
    pub fn holds(&self) -> bool {
        if self.work_limit[0] > self.work_limit[1] {
            return false;
        }
        if self.seen == 0 {
            return self.statuses_equal;
        }
        (self.same >= SAME || self.differ <= 1)
            && self.g_median <= G_MEDIAN
            && self.g_p999 <= G_P999
            && self.t_p999 <= T_P999
            && self.pol_p999 <= POL_P999
            && (self.lit == 0 || self.light_within >= LIGHT_WITHIN)
    }

    pub fn assert_holds(&self) {
        eprintln!("{self:?}");
        assert!(
            self.holds(),
            "{}: the GPU kernel disagrees with the CPU: {self:?}",
            self.name
        );
    }
}

/// A record as bits (NaN equal to itself, −0 told from 0): equal bits, equal bytes in the
/// data file.
pub fn bits(r: &PixelRecord) -> Vec<u32> {
    let values = [r.u, r.v, r.g, r.t_emit, r.x, r.y, r.z, r.lambda, r.cos_i];
    let vectors = r.dir.iter().chain(&r.view).chain(&r.pol);
    let mut v: Vec<u32> = values.iter().chain(vectors).map(|x| x.to_bits()).collect();
    v.extend([r.object as u32, r.status as u32]);
    v
}

/// A scene file of the repository's scenes/ folder.
pub fn example(name: &str) -> Scene {
    let path = testkit::scenes_dir().join(format!("{name}.toml"));
    Scene::from_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A scene from its text.
pub fn scene(text: &str) -> Scene {
    Scene::from_str(text, "test scene").unwrap_or_else(|e| panic!("{e}"))
}

/// `scene` at another image size (its samples per pixel kept).
pub fn sized(mut scene: Scene, width: u32, height: u32) -> Scene {
    scene.camera = scene.camera.with_size(width, height);
    scene
}

/// The GPU render of `scene` with the kernel source `kernel`, unchecked.
pub fn gpu_render(scene: &Scene, kernel: &str) -> gpu::GpuRender {
    gpu::render_with(scene, kernel, &NoProgress)
        .unwrap_or_else(|e| panic!("{}: GPU render failed: {e}", scene.name))
}

/// The CPU exact render of `scene`.
pub fn cpu_render(scene: &Scene) -> DataFile {
    let mut exact = scene.clone();
    exact.trace.method = TraceMethod::Exact;
    exact.trace.gpu = false;
    render(&exact, &NoProgress).expect("CPU render").0
}

/// The GPU render (with the kernel source `kernel`) and the CPU exact render of `scene`.
pub fn both(scene: &Scene, kernel: &str) -> (DataFile, DataFile) {
    (gpu_render(scene, kernel).data, cpu_render(scene))
}

/// Minkowski space, an observer moving at 0.5 c, a ball at rest and one moving at 0.9 c (the
/// scene on which an NVIDIA driver saw every sample hit the second ball).
pub const MINKOWSKI_TWO_BALLS: &str = "name = \"flat\"\n[spacetime]\nmetric = \"minkowski\"\n\
     [observer]\ntime = 0.0\nposition = { x = 0.0, y = 0.0, z = 0.0 }\n\
     velocity = { speed = 0.5, direction = [0, 1, 0] }\nforward = [1, 0, 0]\nup = [0, 0, 1]\n\
     [camera]\nkind = \"pinhole\"\nfov_deg = 90.0\nwidth = 80\nheight = 60\n\
     [trace]\nmax_past = 20.0\n\
     [[object]]\nname = \"still\"\nradius = 0.5\nmotion = { kind = \"rest\", position = { x = 3.0, y = 0.5, z = 0.0 } }\n\
     [[object]]\nname = \"fast\"\nradius = 0.5\nmotion = { kind = \"geodesic\", time = 0.0, position = { x = 4.0, y = -6.0, z = 0.0 }, speed = 0.9, direction = [0, 1, 0] }\n";

/// An observer off the axis moving at 0.6 c, a ball at rest, a falling ball, a floor and a
/// light, at `width` × `height`: a scene with everything the kernel's search and shadow rays
/// do, on which softpipe disagreed with the CPU on a quarter of the samples before the
/// kernel stored at constant indices only.
pub fn off_axis_lit_floor(width: u32, height: u32) -> Scene {
    lit_floor(1.0, 10.0, width, height)
}

/// The same with Gödel's parameter `a` and the trace's `max_past` (the falling ball's radius
/// shrinks with a below 1, as its rest frame's second-order description asks).
pub fn lit_floor(a: f64, max_past: f64, width: u32, height: u32) -> Scene {
    let fall_radius = (0.15 * a).min(0.15);
    scene(&format!(
        "name = \"off-axis-lit-floor\"\n\
         [spacetime]\nmetric = \"godel\"\na = {a}\n\
         [observer]\ntime = 2.0\nposition = {{ r = 0.6, phi = 0.8, z = 0.4 }}\n\
         velocity = {{ speed = 0.6, direction = [0.2, -1, 0.1] }}\nforward = [1, 0, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"panorama\"\nh_fov_deg = 360.0\nv_fov_deg = 90.0\nwidth = {width}\nheight = {height}\n\
         [trace]\nmax_past = {max_past}\n\
         [[object]]\nname = \"rest\"\nradius = 0.2\nmotion = {{ kind = \"rest\", position = {{ r = 0.9, phi = 0.0, z = 0.0 }} }}\n\
         [[object]]\nname = \"falling\"\nradius = {fall_radius}\nmotion = {{ kind = \"geodesic\", time = 0.0, position = {{ x = -0.5, y = 0.5, z = 0.0 }}, speed = 0.8, direction = [1, 0, 0.2] }}\n\
         [[object]]\nname = \"floor\"\nframe = \"coordinates\"\nshape = \"plane\"\nheight = -0.5\nextent = 3.0\n\
         [[light]]\nposition = {{ r = 0.5, phi = 2.0, z = 0.6 }}\npower = 2.0\n"
    ))
}

fn quantile(mut v: Vec<f64>, p: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * p).round() as usize]
}

/// Compares two data files of one scene.
pub fn compare(name: &str, gpu: &DataFile, cpu: &DataFile) -> Agreement {
    assert_eq!((gpu.width, gpu.height), (cpu.width, cpu.height));
    let (mut seen, mut same) = (0usize, 0usize);
    let statuses_equal = (gpu.records.iter().zip(&cpu.records)).all(|(a, b)| a.status == b.status);
    let (mut dg, mut dt, mut dp) = (Vec::new(), Vec::new(), Vec::new());
    for (a, b) in gpu.records.iter().zip(&cpu.records) {
        let hit = |r: &datafile::PixelRecord| r.status == RayStatus::Hit;
        if hit(a) || hit(b) {
            seen += 1;
            if a.status == b.status && a.object == b.object {
                same += 1;
            }
        }
        if hit(a) && hit(b) && a.object == b.object {
            dg.push(((a.g - b.g) / b.g).abs() as f64);
            dt.push(((a.t_emit - b.t_emit).abs() / (1.0 + b.t_emit.abs())) as f64);
            let d = (0..3)
                .map(|i| (a.pol[i] - b.pol[i]).abs())
                .fold(0.0, f32::max);
            // NaN counts as a disagreement.
            dp.push(if d.is_nan() {
                f64::INFINITY
            } else {
                f64::from(d)
            });
        }
    }
    let (mut lit, mut within, mut lit_moved) = (0usize, 0usize, 0usize);
    for (pa, pb) in gpu.lights.iter().zip(&cpu.lights) {
        for i in 0..pa.len() {
            let (a, b) = (gpu.records[i], cpu.records[i]);
            if a.status != RayStatus::Hit || b.status != RayStatus::Hit || a.object != b.object {
                continue;
            }
            let (x, y) = (pa[i], pb[i]);
            if !(x > 0.0 || y > 0.0 || x.is_nan() || y.is_nan()) {
                continue;
            }
            let moved = (a.x - b.x)
                .abs()
                .max((a.y - b.y).abs())
                .max((a.z - b.z).abs());
            // NaN counts as moved.
            if moved.is_nan() || moved > SAME_EVENT {
                lit_moved += 1;
                continue;
            }
            lit += 1;
            let ok = (x.is_nan() && y.is_nan()) || (x - y).abs() <= 1e-3 * y.abs();
            within += usize::from(ok);
        }
    }
    Agreement {
        name: name.to_string(),
        seen,
        same: same as f64 / seen.max(1) as f64,
        differ: seen - same,
        g_median: quantile(dg.clone(), 0.5),
        g_p999: quantile(dg, 0.999),
        t_p999: quantile(dt, 0.999),
        pol_p999: quantile(dp, 0.999),
        lit,
        light_within: within as f64 / lit.max(1) as f64,
        lit_moved,
        statuses_equal,
        work_limit: [gpu, cpu].map(|d| {
            (d.records.iter())
                .filter(|r| r.status == RayStatus::WorkLimit)
                .count()
        }),
    }
}

/// The agreement of the kernel source `kernel` with the CPU on `scene`.
pub fn agreement(scene: &Scene, kernel: &str) -> Agreement {
    let (gpu, cpu) = both(scene, kernel);
    compare(&scene.name, &gpu, &cpu)
}

/// The example scene in the member m² = `ratio`·Ω², its earth made small enough for a local
/// sphere at its speed in every member (m² = 6Ω² has the shortest length scale).
pub fn family_member(ratio: f64) -> scene::Scene {
    let text = std::fs::read_to_string(testkit::scenes_dir().join("godel-type.toml"))
        .expect("the example scene");
    let base = scene(&text);
    let omega = base.metric.godel_type().expect("a member").omega;
    let text = text
        .replace("m2 = 1.0", &format!("m2 = {:?}", ratio * omega * omega))
        .replace(
            "name = \"earth\"\nradius = 0.15",
            "name = \"earth\"\nradius = 0.12",
        );
    let mut s = sized(scene(&text), 110, 13);
    s.name = format!("godel-type m2/omega2 = {ratio}");
    s
}

/// A mutated kernel: `from` replaced by `to` (which must occur once, so that the test follows
/// the kernel's text and mutates what it names).
pub fn mutated(from: &str, to: &str) -> String {
    assert_eq!(
        KERNEL.matches(from).count(),
        1,
        "the kernel no longer has {from:?} once"
    );
    KERNEL.replacen(from, to, 1)
}

/// A mutation must be caught: its kernel disagrees with the CPU on `scene`.
pub fn caught(scene: &scene::Scene, from: &str, to: &str) {
    let a = agreement(scene, &mutated(from, to));
    eprintln!("mutation {from:?} → {to:?}: {a:?}");
    assert!(
        !a.holds(),
        "the mutation {from:?} → {to:?} went unnoticed: {a:?}"
    );
}
