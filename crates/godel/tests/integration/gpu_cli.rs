//! `godel render --gpu` (docs/physics.md, "The GPU kernel"): the same files as a CPU render,
//! records that agree with the CPU exact tracer's, `[trace] gpu = true` and sequences with it,
//! the refusal of --part, and one clear sentence where no EGL library can be loaded (with no
//! file written).

use crate::common::{godel, path_arg, render, stderr};
use datafile::{DataFile, RayStatus};
use std::path::Path;

const SCENE: &str = "name = \"ball\"\n\
[spacetime]\nmetric = \"godel\"\na = 1.0\n\
[observer]\ntime = 0.0\nposition = { r = 0.0, phi = 0.0, z = 0.0 }\nforward = [1, 0, 0]\nup = [0, 0, 1]\n\
[camera]\nkind = \"panorama\"\nh_fov_deg = 360.0\nv_fov_deg = 40.0\nwidth = 180\nheight = 20\n\
[trace]\nmax_past = 8.0\n\
[[object]]\nname = \"ball\"\nradius = 0.2\nmotion = { kind = \"rest\", position = { x = 1.0, y = 0.0, z = 0.0 } }\n\
[[light]]\nposition = { x = 1.0, y = 1.0, z = 0.0 }\npower = 12.0\n";

fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn render_gpu_writes_the_files_of_a_cpu_render_with_records_that_agree() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "ball.toml", SCENE);
    let (gpu, cpu) = (dir.path().join("gpu"), dir.path().join("cpu"));
    let o = render(&scene, &gpu, &["--gpu", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("on the GPU: "), "{}", stderr(&o));
    let o = render(&scene, &cpu, &["--method", "exact", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in ["ball.png", "ball.exr"] {
        assert!(gpu.join(name).is_file(), "{name} missing");
    }
    let a = DataFile::read(&gpu.join("ball.exr")).unwrap();
    let b = DataFile::read(&cpu.join("ball.exr")).unwrap();
    assert_eq!(a.header.method, "gpu");
    assert_eq!(
        (a.width, a.height, a.lights.len()),
        (b.width, b.height, b.lights.len())
    );
    // The file declares the polarization channels (read back from the EXR), as a CPU one.
    assert!(a.polarization && b.polarization);
    let hits = a
        .records
        .iter()
        .filter(|r| r.status == RayStatus::Hit)
        .count();
    assert!(hits > 100, "{hits}");
    for (i, (x, y)) in a.records.iter().zip(&b.records).enumerate() {
        assert_eq!((x.status, x.object), (y.status, y.object), "sample {i}");
        if x.status == RayStatus::Hit {
            assert!(
                (x.g - y.g).abs() < 1e-5 && (x.t_emit - y.t_emit).abs() < 1e-5,
                "sample {i}"
            );
            let dp = (0..3)
                .map(|c| (x.pol[c] - y.pol[c]).abs())
                .fold(0.0, f32::max);
            assert!(dp < 1e-4, "sample {i}: pol {:?} vs {:?}", x.pol, y.pol);
            let (la, lb) = (a.lights[0][i], b.lights[0][i]);
            assert!(
                (la - lb).abs() <= 1e-3 * lb.abs() + 1e-6,
                "sample {i}: light {la} vs {lb}"
            );
        }
    }
}

#[test]
fn trace_gpu_in_the_scene_traces_on_the_gpu_also_in_sequences() {
    let dir = tempfile::tempdir().unwrap();
    let text = SCENE.replace("max_past = 8.0\n", "max_past = 8.0\ngpu = true\n");
    let scene = write(dir.path(), "ball.toml", &text);
    let o = render(&scene, &dir.path().join("out"), &["-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("on the GPU: "), "{}", stderr(&o));
    let data = DataFile::read(&dir.path().join("out/ball.exr")).unwrap();
    assert_eq!(data.header.method, "gpu");
    let script = write(
        dir.path(),
        "seq.toml",
        "output = \"frames\"\nframes = 2\nmp4 = false\n[trace]\nscene = \"ball.toml\"\nobserver_time = [0.0, 0.5]\nkeep_data = true\n",
    );
    let o = godel(&["sequence", path_arg(&script), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    for frame in ["frame_0000", "frame_0001"] {
        let data = DataFile::read(&dir.path().join(format!("frames/{frame}.exr"))).unwrap();
        assert_eq!(data.header.method, "gpu", "{frame}");
    }
}

#[test]
fn gpu_and_parts_exclude_each_other() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "ball.toml", SCENE);
    let o = render(&scene, &dir.path().join("out"), &["--gpu", "--part", "1/2"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--gpu") && stderr(&o).contains("--part"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.path().join("out").exists());
}

/// Without an EGL library each way of asking for the GPU fails with one sentence that names
/// what asked (`--gpu`, or the scene's `[trace] gpu = true`, also in a sequence: issue 36
/// found the sequence blaming `--gpu`), and writes nothing: not even the output folder it
/// created (issue 36 found it left empty).
#[test]
fn without_an_egl_library_gpu_fails_with_one_sentence_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "ball.toml", SCENE);
    let in_scene = SCENE.replace("max_past = 8.0\n", "max_past = 8.0\ngpu = true\n");
    let gpu_scene = write(dir.path(), "gpu.toml", &in_scene);
    let script = write(
        dir.path(),
        "seq.toml",
        "output = \"new/frames\"\nframes = 2\nmp4 = false\n[trace]\nscene = \"gpu.toml\"\nobserver_time = [0.0, 0.5]\n",
    );
    let out = dir.path().join("new/out");
    let cases: [(Vec<&str>, String); 3] = [
        (
            vec![
                "render",
                path_arg(&scene),
                "-o",
                path_arg(&out),
                "--gpu",
                "-q",
            ],
            "error: --gpu: tracing on the GPU needs the EGL library".into(),
        ),
        (
            vec!["render", path_arg(&gpu_scene), "-o", path_arg(&out), "-q"],
            format!(
                "error: {}: [trace] gpu = true: tracing on the GPU needs the EGL library",
                gpu_scene.display()
            ),
        ),
        (
            vec!["sequence", path_arg(&script), "-q"],
            format!(
                "error: frame 0: {}: [trace] gpu = true: tracing on the GPU needs the EGL library",
                gpu_scene.display()
            ),
        ),
    ];
    for (args, start) in cases {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_godel"))
            .args(&args)
            .env("GODEL_EGL", dir.path().join("no-such-libEGL.so.1"))
            .output()
            .unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with(&start), "{args:?}: {err}");
        assert!(!err.contains("--gpu") || args.contains(&"--gpu"), "{err}");
        assert!(
            !dir.path().join("new").exists(),
            "{args:?}: a folder was left"
        );
    }
}

/// Issue 36: an empty `GODEL_EGL` loaded the godel binary itself as the EGL library
/// ("undefined symbol: eglChooseConfig"); empty means unset, the default library.
#[test]
fn an_empty_godel_egl_is_the_default_library() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "ball.toml", SCENE);
    let out = dir.path().join("out");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_godel"))
        .args([
            "render",
            path_arg(&scene),
            "-o",
            path_arg(&out),
            "--gpu",
            "-q",
        ])
        .args(["--width", "36", "--height", "4"])
        .env("GODEL_EGL", "")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        DataFile::read(&out.join("ball.exr")).unwrap().header.method,
        "gpu"
    );
}

/// A stereo pair on the GPU: each eye traced by the kernel (and checked against the CPU) as
/// its own scene, its records those of the CPU exact tracer's same eye.
#[test]
fn render_gpu_traces_both_eyes_of_a_stereo_pair() {
    let dir = tempfile::tempdir().unwrap();
    let text = SCENE.replace(
        "height = 20\n",
        "height = 20\nstereo = { separation = 0.2 }\n",
    );
    let scene = write(dir.path(), "ball.toml", &text);
    let (gpu, cpu) = (dir.path().join("gpu"), dir.path().join("cpu"));
    let o = render(&scene, &gpu, &["--gpu", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = render(&scene, &cpu, &["--method", "exact", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        crate::common::png(&gpu.join("ball.png")).dimensions(),
        (360, 20)
    );
    let mut eyes = Vec::new();
    for eye in ["left", "right"] {
        let name = format!("ball.{eye}.exr");
        let a = DataFile::read(&gpu.join(&name)).unwrap();
        let b = DataFile::read(&cpu.join(&name)).unwrap();
        assert_eq!(a.header.method, "gpu");
        let same = a.records.iter().zip(&b.records);
        for (i, (x, y)) in same.enumerate() {
            assert_eq!(
                (x.status, x.object),
                (y.status, y.object),
                "{eye} eye, sample {i}"
            );
        }
        eyes.push(
            a.records
                .iter()
                .filter(|r| r.status == RayStatus::Hit)
                .count(),
        );
    }
    assert!(eyes[0] > 50 && eyes[0] != eyes[1], "hits per eye {eyes:?}");
}

/// A Gödel-type member (issue 34) is traced by the kernel: `--gpu` and `[trace] gpu = true`
/// render the lit member, its records and light plane as the CPU exact tracer's (the check
/// every GPU render passes, and here sample by sample); a ball falling fast enough to escape a
/// causal member, which the kernel's escape stop cannot bound, is refused with one sentence
/// naming the reason and what to do, before anything is traced or written.
#[test]
fn the_kernel_traces_godel_type_members_and_refuses_an_escaping_ball_with_one_sentence() {
    let dir = tempfile::tempdir().unwrap();
    let member = SCENE.replace(
        "metric = \"godel\"\na = 1.0",
        "metric = \"godel-type\"\nm2 = 1.0\nomega = 0.7071067811865476",
    );
    assert!(member.contains("[[light]]"));
    let scene = write(dir.path(), "member.toml", &member);
    let (gpu, cpu) = (dir.path().join("gpu"), dir.path().join("cpu"));
    let o = render(&scene, &gpu, &["--gpu", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = render(&scene, &cpu, &["--method", "exact", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (a, b) = (
        DataFile::read(&gpu.join("ball.exr")).unwrap(),
        DataFile::read(&cpu.join("ball.exr")).unwrap(),
    );
    assert_eq!(a.header.method, "gpu");
    assert_eq!(a.header.metric, "godel-type");
    let m = a.header.member.expect("the member in the header");
    assert_eq!((m.m2, m.omega), (1.0, std::f64::consts::FRAC_1_SQRT_2));
    let hits = |d: &DataFile| {
        d.records
            .iter()
            .filter(|r| r.status == RayStatus::Hit)
            .count()
    };
    assert!(hits(&b) > 50, "{} hits", hits(&b));
    let same = (a.records.iter().zip(&b.records))
        .filter(|(x, y)| x.status == y.status && x.object == y.object)
        .count();
    assert_eq!(same, a.records.len(), "records differ");
    let lit = (0..a.records.len())
        .filter(|&i| b.lights[0][i] > 0.0)
        .count();
    assert!(lit > 20, "{lit} lit");
    for i in 0..a.records.len() {
        let (x, y) = (a.lights[0][i], b.lights[0][i]);
        assert!(
            (x - y).abs() <= 1e-3 * y.abs() + 1e-9,
            "sample {i}: light {x} on the GPU, {y} on the CPU"
        );
    }
    // The same from the scene's own [trace] gpu = true.
    let in_scene = write(
        dir.path(),
        "in-scene.toml",
        &member.replace("max_past = 8.0", "max_past = 8.0\ngpu = true"),
    );
    let o = render(&in_scene, &dir.path().join("in-scene"), &["-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // m² = 6Ω² is causal; at 0.9 c across the axis Λ = γ²(Ω² − (m²/4)v²) < 0: the ball escapes.
    let escaping = member.replace("m2 = 1.0", "m2 = 3.0").replace(
        "[[light]]",
        "[[object]]\nname = \"fast\"\nradius = 0.05\nmotion = { kind = \"geodesic\", time = 0.0, \
         position = { x = -0.5, y = 0.0, z = 0.0 }, speed = 0.9, direction = [0, 1, 0] }\n[[light]]",
    );
    let scene = write(dir.path(), "escaping.toml", &escaping);
    let out = dir.path().join("out");
    let o = render(&scene, &out, &["--gpu"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--gpu") && err.contains("escape") && err.contains("without --gpu"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(!out.exists());
}
