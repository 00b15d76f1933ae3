//! The check every GPU render passes before it is used (`gpu::check`): a kernel that traces
//! correctly passes it, and one that runs wrongly (objects moved, as a driver that miscompiles
//! the kernel would) is refused with a message naming the renderer and a disagreeing sample.

use gpu::check::{against_cpu, allowed, CheckError};
use render::driver::NoProgress;
use scene::Scene;

fn scene(name: &str, width: u32, height: u32) -> Scene {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    let mut scene = Scene::from_file(&path).expect("scene");
    scene.camera = scene.camera.with_size(width, height);
    scene.samples = 1;
    scene
}

#[test]
fn a_correct_trace_passes_and_a_wrong_one_is_refused() {
    for (name, w, h) in [
        ("static-sphere", 160, 20),
        ("lit-shadow", 180, 20),
        ("reference", 110, 13),
    ] {
        let scene = scene(name, w, h);
        let good = gpu::render_with(&scene, gpu::KERNEL, &NoProgress).expect("GPU render");
        against_cpu(&scene, &good.data.records, &good.renderer)
            .unwrap_or_else(|e| panic!("{name}: the kernel as shipped is refused: {e}"));
        assert!(
            gpu::render(&scene, &NoProgress).is_ok(),
            "{name}: render refuses the kernel"
        );
    }
    // Balls at rest moved up by 0.15 a: the samples along their edges change.
    let moved = gpu::KERNEL.replace(
        "t0.y, t0.z, vec4(0.0, t1.xyz),",
        "t0.y, t0.z, vec4(0.0, t1.xyz + vec3(0.0, 0.0, 0.15)),",
    );
    assert_ne!(moved, gpu::KERNEL, "the mutation applies");
    for (name, w, h) in [("static-sphere", 160, 20), ("lit-shadow", 180, 20)] {
        let scene = scene(name, w, h);
        let wrong = gpu::render_with(&scene, &moved, &NoProgress).expect("GPU render");
        match against_cpu(&scene, &wrong.data.records, &wrong.renderer) {
            Err(CheckError::Disagrees {
                differ,
                checked,
                renderer,
                ..
            }) => {
                assert!(differ > allowed(checked), "{name}: {differ} of {checked}");
                assert_eq!(renderer, wrong.renderer);
                let message = CheckError::Disagrees {
                    renderer,
                    checked,
                    differ,
                    col: 0,
                    row: 0,
                    gpu: "hit object 0".into(),
                    cpu: "escaped".into(),
                }
                .to_string();
                assert!(
                    message.contains("disagrees with the CPU exact tracer on"),
                    "{message}"
                );
                assert!(
                    !message.contains("--gpu"),
                    "a library's message gives no CLI advice: {message}"
                );
            }
            other => panic!("{name}: a moved ball passes the check: {other:?}"),
        }
    }
}

#[test]
fn two_percent_and_at_least_two_disagreements_are_allowed() {
    assert_eq!(allowed(10), 2);
    assert_eq!(allowed(100), 2);
    assert_eq!(allowed(256), 5);
}

#[test]
fn samples_the_gpu_left_out_of_work_are_disagreements() {
    // The kernel's bounds are the CPU's: a sample out of work where the CPU finished is
    // wrong, as a wrong hit is (docs/physics.md, "Bounds of a GPU").
    let scene = scene("static-sphere", 160, 20);
    let mut exact = scene.clone();
    exact.trace.method = scene::TraceMethod::Exact;
    let (cpu, _) = render::driver::render(&exact, &NoProgress).expect("CPU render");
    against_cpu(&scene, &cpu.records, "the CPU").expect("the CPU's own records pass");
    let mut records = cpu.records.clone();
    for r in records.iter_mut().step_by(10) {
        *r = datafile::PixelRecord::miss(datafile::RayStatus::WorkLimit);
    }
    match against_cpu(&scene, &records, "a GPU") {
        Err(CheckError::Disagrees {
            differ,
            checked,
            gpu,
            ..
        }) => {
            assert!(differ > allowed(checked), "{differ} of {checked}");
            assert_eq!(gpu, "out of work (work limit)");
        }
        other => panic!("samples out of work pass the check: {other:?}"),
    }
}
