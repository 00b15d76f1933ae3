//! Traces a scene with the GPU kernel and the CPU exact tracer and prints how they agree.
//! `cargo run --release -p gpu --example against_cpu -- SCENE.toml [WIDTH HEIGHT]`
//! With `KERNEL=FILE` it traces with that kernel source instead of `gpu::KERNEL`; the digest
//! it prints of the GPU's records and lights tells two kernels' traces apart bit for bit.

use datafile::record::RayStatus;
use render::driver::{render, NoProgress};
use scene::{Scene, TraceMethod};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let text = std::fs::read_to_string(&args[1]).expect("scene");
    let mut scene = Scene::from_str(&text, &args[1]).expect("valid scene");
    if args.len() >= 4 {
        let (w, h) = (args[2].parse().unwrap(), args[3].parse().unwrap());
        scene.camera = scene.camera.with_size(w, h);
    }
    scene.trace.method = TraceMethod::Exact;
    let t = Instant::now();
    let gpu = gpu::GpuTracer::with_kernel(
        gpu::KernelInput::new(&scene),
        &std::env::var("KERNEL")
            .map(|p| std::fs::read_to_string(p).expect("kernel file"))
            .unwrap_or(gpu::KERNEL.to_string()),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let setup = t.elapsed();
    let t = Instant::now();
    // BUDGET=N, SIDE=N: cut the work so (the records must not change).
    let env = |name: &str| std::env::var(name).ok().map(|v| v.parse().expect(name));
    let mut tiling = gpu::Tiling {
        side: env("SIDE"),
        ..Default::default()
    };
    if let Some(b) = env("BUDGET") {
        tiling.first_budget = b as i32;
    }
    let g = gpu.trace_with(&NoProgress, tiling).expect("trace");
    let tg = t.elapsed();
    let t = Instant::now();
    let (cpu, _) = render(&scene, &NoProgress).expect("cpu");
    let tc = t.elapsed();
    let n = g.records.len();
    if std::env::var("SHOWWL").is_ok() {
        let bad: Vec<usize> = (0..g.records.len())
            .filter(|&i| g.records[i].status != cpu.records[i].status)
            .take(10)
            .collect();
        println!("mismatched pixels: {bad:?}");
    }
    if std::env::var("USED").is_ok() {
        for (c, name) in [(1usize, "probes"), (2, "loop passes")] {
            let mut v: Vec<f32> = g
                .records
                .iter()
                .filter(|r| r.status == RayStatus::Hit)
                .map(|r| r.dir[c])
                .collect();
            v.sort_by(f32::total_cmp);
            if !v.is_empty() {
                let at = |p: f64| v[((v.len() - 1) as f64 * p) as usize];
                println!(
                    "{name} (hit samples): median {} p90 {} p99 {} max {}",
                    at(0.5),
                    at(0.9),
                    at(0.99),
                    at(1.0)
                );
                let arg = (0..g.records.len())
                    .filter(|&i| g.records[i].status == RayStatus::Hit)
                    .max_by(|&a, &b| g.records[a].dir[c].total_cmp(&g.records[b].dir[c]));
                println!("  heaviest sample: {arg:?}");
            }
        }
    }
    if let Ok(i) = std::env::var("PIXEL") {
        let i: usize = i.parse().unwrap();
        println!("gpu {:?}\ncpu {:?}", g.records[i], cpu.records[i]);
    }
    let (mut same, mut dg, mut dt, mut hits) = (0, Vec::new(), Vec::new(), 0);
    let mut statuses = std::collections::BTreeMap::new();
    for (a, b) in g.records.iter().zip(&cpu.records) {
        *statuses
            .entry((a.status as u32, b.status as u32))
            .or_insert(0) += 1;
        if a.status == b.status && a.object == b.object {
            same += 1;
            if a.status == RayStatus::Hit {
                hits += 1;
                dg.push(((a.g - b.g) / b.g).abs());
                dt.push((a.t_emit - b.t_emit).abs() / (1.0 + b.t_emit.abs()));
            }
        }
    }
    if std::env::var("SHOWG").is_ok() {
        let mut shown = 0;
        for i in 0..n {
            let (a, b) = (&g.records[i], &cpu.records[i]);
            if a.status == RayStatus::Hit
                && b.status == RayStatus::Hit
                && ((a.g - b.g) / b.g).abs() > 1e-3
                && shown < 8
            {
                shown += 1;
                println!(
                    "  g px {i}: gpu g {} t {} uv ({}, {}) | cpu g {} t {} uv ({}, {})",
                    a.g, a.t_emit, a.u, a.v, b.g, b.t_emit, b.u, b.v
                );
            }
        }
    }
    let q = |v: &mut Vec<f32>, p: f64| {
        v.sort_by(f32::total_cmp);
        if v.is_empty() {
            f32::NAN
        } else {
            v[((v.len() - 1) as f64 * p) as usize]
        }
    };
    println!(
        "{}: {} samples on {}, gpu {:.3}s (+{:.3}s setup, {} rounds), cpu {:.3}s",
        args[1],
        n,
        gpu.renderer(),
        tg.as_secs_f64(),
        setup.as_secs_f64(),
        g.rounds,
        tc.as_secs_f64()
    );
    // Debug prints each f32 so that it reads back to the same bits.
    let mut digest = std::collections::hash_map::DefaultHasher::new();
    std::hash::Hash::hash(&format!("{:?} {:?}", g.records, g.lights), &mut digest);
    println!("gpu digest {:016x}", std::hash::Hasher::finish(&digest));
    println!(
        "same object+status {:.4}% ; hits {hits}; statuses (gpu,cpu)->n {:?}",
        100.0 * same as f64 / n as f64,
        statuses
    );
    println!(
        "dg/g median {:e} p99.9 {:e} max {:e}",
        q(&mut dg, 0.5),
        q(&mut dg, 0.999),
        q(&mut dg, 1.0)
    );
    println!(
        "dt/(1+|t|) median {:e} p99.9 {:e} max {:e}",
        q(&mut dt, 0.5),
        q(&mut dt, 0.999),
        q(&mut dt, 1.0)
    );
    for k in 0..g.lights.len() {
        let mut dl = Vec::new();
        for i in 0..n {
            if g.records[i].status == RayStatus::Hit
                && cpu.records[i].status == RayStatus::Hit
                && g.records[i].object == cpu.records[i].object
            {
                let (a, b) = (g.lights[k][i], cpu.lights[k][i]);
                if b > 0.0 || a > 0.0 || a.is_nan() != b.is_nan() {
                    let e = if a.is_nan() && b.is_nan() {
                        0.0
                    } else {
                        (a - b).abs() / b.abs().max(1e-6)
                    };
                    let e = if e.is_nan() { 1e9 } else { e };
                    if e > 1e-3
                        && std::env::var("SHOWBAD").is_ok()
                        && dl.iter().filter(|&&v| v > 1e-3).count() < 8
                    {
                        println!("  bad px {i}: gpu {a} cpu {b}");
                    }
                    dl.push(e);
                }
            }
        }
        let mut shown = 0;
        for i in (0..n).step_by(97) {
            if g.records[i].status == RayStatus::Hit && shown < 6 && std::env::var("SHOW").is_ok() {
                shown += 1;
                println!("  px {i}: gpu {} cpu {}", g.lights[k][i], cpu.lights[k][i]);
            }
        }
        println!(
            "light {k}: above 1e-3: {}",
            dl.iter().filter(|&&v| v > 1e-3).count()
        );
        println!(
            "light {k}: n {} rel median {:e} p99.9 {:e} max {:e}",
            dl.len(),
            q(&mut dl, 0.5),
            q(&mut dl, 0.999),
            q(&mut dl, 1.0)
        );
    }
}
