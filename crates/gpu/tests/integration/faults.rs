//! Faults a driver may make, injected into the kernel's text: each is harmless by
//! construction or caught both by the agreement comparison with the CPU exact tracer and by
//! the check every GPU render passes (docs/physics.md, "The GPU kernel").
//!
//! - Stores lost: the probe buffers' stores dropped (softpipe misplaced the earlier kernel's
//!   stores at runtime indices, and dropping those gives an NVIDIA driver's wrong records;
//!   today's kernel has no such store: `kernel_rules.rs`): caught.
//! - A NaN-blind finiteness test (as a compiler that assumes no NaN makes of `isnan`): no
//!   record changes, since no NaN reaches a finiteness test on this scene.
//! - A probe answering NaN (inside the objects, and at one probe in eight): caught, and no
//!   record is wrong: the search stops at the NaN and marks its sample failed.

use crate::common::{bits, compare, cpu_render, gpu_render, off_axis_lit_floor};
use datafile::{DataFile, RayStatus};
use gpu::check::{against_cpu, CheckError};
use gpu::KERNEL;

/// `kernel` with `from` replaced by `to` (which must occur once).
fn injected(kernel: &str, from: &str, to: &str) -> String {
    assert_eq!(
        kernel.matches(from).count(),
        1,
        "the kernel no longer has {from:?} once"
    );
    kernel.replacen(from, to, 1)
}

/// The scene of these tests: every kind of search (balls at rest and falling, a plane, shadow
/// rays) seen by a moving observer, large enough for the check to sample many hits.
fn frame() -> scene::Scene {
    off_axis_lit_floor(48, 16)
}

/// The fault in `kernel` is caught: the comparison with the CPU fails and the check refuses.
/// Returns the kernel's render.
fn caught(kernel: &str) -> DataFile {
    let scene = frame();
    let gpu = gpu_render(&scene, kernel);
    let a = compare(&scene.name, &gpu.data, &cpu_render(&scene));
    eprintln!("{a:?}");
    assert!(!a.holds(), "the comparison misses the fault: {a:?}");
    match against_cpu(&scene, &gpu.data.records, &gpu.renderer) {
        Err(CheckError::Disagrees {
            differ, checked, ..
        }) => eprintln!("check: {differ} of {checked}"),
        other => panic!("the check misses the fault: {other:?}"),
    }
    gpu.data
}

/// A probe's signed distance made NaN where `condition` (GLSL, of the probe's `p` and its
/// event `x`) holds.
fn probe_nan(condition: &str) -> String {
    let signature = "Probe probeObject(int i, vec4 x, vec4 k, float pt, float tauSeed) {";
    injected(
        KERNEL,
        signature,
        &format!(
            "Probe probeAnswer(int i, vec4 x, vec4 k, float pt, float tauSeed);\n\
             Probe probeObject(int i, vec4 x, vec4 k, float pt, float tauSeed) {{\n\
                 Probe p = probeAnswer(i, x, k, pt, tauSeed);\n\
                 if ({condition}) p.f = uintBitsToFloat(floatBitsToUint(p.f) | 0x7fc00000u);\n\
                 return p;\n\
             }}\n\
             Probe probeAnswer(int i, vec4 x, vec4 k, float pt, float tauSeed) {{"
        ),
    )
}

#[test]
fn a_driver_that_loses_the_probe_stores_is_caught() {
    let stores = [
        "            startProbe[j] = p;\n            startAt[j] = at;\n",
        "            endProbe[j] = p;\n            endAt[j] = at;\n",
    ];
    caught(&injected(&injected(KERNEL, stores[0], ""), stores[1], ""));
}

/// A probe answering NaN inside the objects (as a square root of a negative number would) and
/// at one probe in eight elsewhere is caught, and harmless: every sample is the shipped
/// kernel's, bit for bit, or marked failed (the search stops at the NaN), never a wrong hit
/// or miss.
#[test]
fn a_probe_answering_nan_is_caught_and_its_samples_marked_failed() {
    let faulty = caught(&probe_nan("p.f < 0.0 || (floatBitsToUint(x.x) & 7u) == 0u"));
    let shipped = gpu_render(&frame(), KERNEL).data;
    let failed = (faulty.records.iter().zip(&shipped.records))
        .filter(|(f, s)| f.status == RayStatus::Failed && s.status != RayStatus::Failed)
        .count();
    let same = (faulty.records.iter().zip(&shipped.records))
        .filter(|(f, s)| bits(f) == bits(s))
        .count();
    assert!(failed > 0);
    assert_eq!(
        same + failed,
        shipped.records.len(),
        "{failed} failed, {same} the same"
    );
}

#[test]
fn a_nan_blind_finiteness_test_changes_no_record() {
    let blind = injected(
        KERNEL,
        "bool finite(float v) { return (floatBitsToUint(v) & 0x7fffffffu) < 0x7e967699u; }",
        "bool finite(float v) { return !(abs(v) >= 1e38); }",
    );
    let scene = frame();
    let shipped = gpu_render(&scene, KERNEL).data;
    let faulty = gpu_render(&scene, &blind).data;
    // llvmpipe's loop limit cuts samples short by the compiled code's shape: those marked
    // out of work on either side are no record of the fault.
    let mut compared = 0;
    for (i, (f, s)) in faulty.records.iter().zip(&shipped.records).enumerate() {
        if f.status == RayStatus::WorkLimit || s.status == RayStatus::WorkLimit {
            continue;
        }
        compared += 1;
        assert_eq!(bits(f), bits(s), "sample {i}");
        for (pf, ps) in faulty.lights.iter().zip(&shipped.lights) {
            assert_eq!(pf[i].to_bits(), ps[i].to_bits(), "sample {i}'s light");
        }
    }
    assert!(
        compared * 10 > shipped.records.len() * 9,
        "{compared} compared"
    );
}
