//! The GPU kernel against the CPU exact tracer on a second, independent compiler: Mesa's
//! softpipe (`GALLIUM_DRIVER=softpipe`, in the same libgl1-mesa-dri as llvmpipe), which
//! interprets the shader through TGSI where llvmpipe compiles it with LLVM. An earlier kernel
//! that stored into arrays at runtime indices ran wrongly there, as it did on an NVIDIA driver
//! (docs/physics.md, "The GPU kernel"); these frames, each with the tolerances of the agreement
//! suite and the check every GPU render passes, refused it. Softpipe is slow (a few thousand
//! rays a second), so the frames are small.
//!
//! Mesa picks its driver when a process first opens a display, so the test runs itself again
//! in a process of its own with GALLIUM_DRIVER=softpipe.

use crate::common::{
    self, compare, cpu_render, example, gpu_render, off_axis_lit_floor, scene, sized,
};
use gpu::KERNEL;
use std::process::Command;

const DRIVER_VAR: &str = "GALLIUM_DRIVER";
const DRIVER: &str = "softpipe";

/// The small frames: balls at rest and their shadows, a falling ball, Minkowski's straight
/// rays with a ball at rest and a fast one, the off-axis observer's lit floor, and a falling
/// earth and a ball at rest in a Gödel-type member on the sphere (m² = −Ω²), lit: the largest
/// kernel a host builds (softpipe's compiler crashed on an earlier one).
fn frames() -> Vec<scene::Scene> {
    let mut reference = sized(example("reference"), 44, 5);
    reference.samples = 1;
    vec![
        sized(example("lit-shadow"), 80, 10),
        reference,
        sized(scene(common::MINKOWSKI_TWO_BALLS), 32, 24),
        off_axis_lit_floor(24, 8),
        lit_member(),
    ]
}

/// The family's example on the sphere with a light.
fn lit_member() -> scene::Scene {
    let text = format!(
        "{}[[light]]\nposition = {{ x = 0.6, y = 0.4, z = 0.3 }}\npower = 6.0\n",
        common::family_member(-1.0).source_text
    );
    let mut s = sized(scene(&text), 44, 5);
    s.name = "lit member".to_string();
    s
}

#[test]
fn small_frames_agree_on_softpipe() {
    let name = "agreement_on_softpipe::small_frames_agree_on_softpipe";
    if std::env::var(DRIVER_VAR).as_deref() != Ok(DRIVER) {
        let exe = std::env::current_exe().expect("the test binary");
        let out = Command::new(exe)
            .args([name, "--exact", "--nocapture", "--test-threads=1"])
            .env(DRIVER_VAR, DRIVER)
            .output()
            .expect("the test binary runs again");
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        eprintln!("{text}");
        assert!(out.status.success(), "on {DRIVER}: {text}");
        assert!(
            text.contains("1 passed"),
            "the test did not run on {DRIVER}: {text}"
        );
        return;
    }
    for scene in frames() {
        let started = std::time::Instant::now();
        let gpu = gpu_render(&scene, KERNEL);
        assert_eq!(
            gpu.renderer, DRIVER,
            "{DRIVER_VAR} does not choose the driver"
        );
        let cpu = cpu_render(&scene);
        let a = compare(&scene.name, &gpu.data, &cpu);
        eprintln!("{:.1} s", started.elapsed().as_secs_f64());
        a.assert_holds();
        assert!(a.seen > 20, "{a:?}");
        if let Err(e) = gpu::check::against_cpu(&scene, &gpu.data.records, &gpu.renderer) {
            panic!(
                "{}: the check refuses the kernel on {DRIVER}: {e}",
                scene.name
            );
        }
    }
}
