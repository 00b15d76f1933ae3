//! The end probe a bisection keeps for a right half (render_intersect.glsl's `pending`;
//! docs/physics.md, "The GPU kernel"): the probe the parent's halving took at that λ, where
//! the kernel once probed it again. Kept or probed again, it is a probe of the same ray point
//! (probed again it starts its simultaneity search from another τ seed, which moves a
//! falling ball's distance by f32 rounding), so every record is the same hit or miss, its
//! event the same within the refinement's bracket, nearly all the same bits, and the probes
//! fall.

use crate::common;
use datafile::{PixelRecord, RayStatus};
use gpu::{GpuTracer, KernelInput, KERNEL};
use render::driver::NoProgress;
use scene::Scene;

/// The line that keeps a probe for the right half of a halving.
const KEEP: &str = "                    pendingDepth = bis.depth + 1;\n";

/// The records of `scene` traced by `kernel`, and its probes in all.
fn traced(scene: &Scene, kernel: &str) -> (Vec<PixelRecord>, f64) {
    let input = KernelInput::new(scene);
    let records = GpuTracer::with_kernel(input.clone(), kernel)
        .expect("a GPU context")
        .trace(&NoProgress)
        .expect("trace")
        .records;
    let counted = GpuTracer::count_probes(input, kernel).expect("trace");
    (records, counted.probes)
}

/// Whether two records are the same hit or miss of the same object, a hit's event and
/// parameter within the kernel's refinement of a crossing of each other (it stops at a
/// bracket of 4 f32 ULP of λ, here from other end values: 64 f32 epsilons of the value or 1).
fn same_hit(k: &PixelRecord, p: &PixelRecord) -> bool {
    let place = |r: &PixelRecord| [r.t_emit, r.x, r.y, r.z, r.lambda];
    let close = |a: f32, b: f32| (a - b).abs() <= 64.0 * f32::EPSILON * a.abs().max(1.0);
    k.status == p.status
        && k.object == p.object
        && (k.status != RayStatus::Hit
            || place(k).into_iter().zip(place(p)).all(|(a, b)| close(a, b)))
}

#[test]
fn kept_end_probes_change_no_record_and_save_probes() {
    assert_eq!(
        KERNEL.matches(KEEP).count(),
        1,
        "the kernel keeps its probes so"
    );
    let again = KERNEL.replace(KEEP, "");
    // A falling ball (whose probes take τ seeds), and a lit floor (the shadow rays' searches).
    let scenes = [
        common::sized(common::example("reference"), 96, 24),
        common::off_axis_lit_floor(48, 16),
    ];
    for scene in scenes {
        let (kept, kept_probes) = traced(&scene, KERNEL);
        let (probed, probed_probes) = traced(&scene, &again);
        let hits = kept.iter().filter(|r| r.status == RayStatus::Hit).count();
        assert!(hits > 20, "{}: {hits} hits", scene.name);
        let differ: Vec<String> = (kept.iter().zip(&probed).enumerate())
            .filter(|(_, (k, p))| !same_hit(k, p))
            .map(|(i, (k, p))| format!("sample {i}: {k:?} against {p:?}"))
            .collect();
        let bits = (kept.iter().zip(&probed))
            .filter(|(k, p)| common::bits(k) == common::bits(p))
            .count();
        eprintln!(
            "{}: probes {probed_probes} → {kept_probes}; {bits} of {} records the same bits",
            scene.name,
            kept.len()
        );
        assert!(differ.is_empty(), "{}: {}", scene.name, differ.join("\n"));
        assert!(
            bits as f64 >= 0.99 * kept.len() as f64,
            "{}: {bits} of {} the same bits",
            scene.name,
            kept.len()
        );
        assert!(
            kept_probes < 0.9 * probed_probes,
            "{}: {kept_probes} probes kept against {probed_probes}",
            scene.name
        );
    }
}
