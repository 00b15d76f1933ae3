//! The page traces on the GPU (page/trace.js running the `gpu` crate's kernel in WebGL2, on
//! SwiftShader here) what `godel render --method exact` traces: example scenes at small sizes
//! — the reference scene (free fall, 2×2 samples a pixel), lit ones (direct light, a shadow
//! in space and time), surroundings (the observer inside a sphere) and a lit Gödel-type member
//! — each against its data
//! file, measured and held to issue 22's tolerances exactly as the `gpu` crate's own agreement
//! tests do (crates/gpu/tests/integration/common.rs, included here): the same object and status on ≥ 99.5 %
//! of the samples either sees an object in, |Δg|/g median ≤ 1e-4 and ≤ 1e-3 on 99.9 %,
//! |Δt_emit| ≤ 1e-4·(1 + |t_emit|) on 99.9 %, light within 1e-3 relative on 99.9 % of the lit
//! samples (docs/physics.md, "The GPU kernel"). The traced slots are read back by the test
//! script only; the page shades them where they are.
//!
//! And a traced frame is shaded as a data file's frame is: with every layer on, the page's
//! picture of it equals the `shade` crate's picture of the traced records within one 8-bit
//! step (the conversion into the shading's channels loses nothing), it is on the canvas, and
//! it matches the picture of the file's own frame but where the two tracers' records differ.
//! Where WebGL2 cannot draw into float textures the page says so and shows the file's frame.

use std::path::Path;

use crate::browser_support::*;
#[path = "../../../../gpu/tests/integration/common.rs"]
#[allow(dead_code)] // the gpu crate's test helpers: this binary uses their comparison only
pub(super) mod kernel_agreement;
use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;
use shade::{ShadeSettings, Shading};

/// Example scenes and the sizes they are traced at here (SwiftShader is slow): free fall
/// with 2×2 samples a pixel, light, a shadow, the observer inside a sphere, and a lit
/// Gödel-type member (m² = 0) with its shadow. The first is also shaded.
const CASES: [(&str, u32, u32); 5] = [
    ("lit-side", 180, 20),
    ("reference", 110, 13),
    ("lit-shadow", 180, 20),
    ("surroundings", 120, 30),
    ("lit-godel-type", 180, 20),
];

/// Channels per slot of a record (gpu::input::SLOT_CHANNELS).
const SLOT: usize = 4;

/// The data file `data` with the records and light planes of a traced frame's slots, read
/// as the `gpu` crate's host reads them.
pub(super) fn traced_file(data: &DataFile, slots: &[Vec<f32>]) -> DataFile {
    let samples = data.width * data.height;
    let channels =
        |s: usize, i: usize| -> [f32; 4] { slots[s][i * SLOT..(i + 1) * SLOT].try_into().unwrap() };
    let records: Vec<PixelRecord> = (0..samples)
        .map(|i| gpu::host::sample_record(|s| channels(s, i)))
        .collect();
    let lights = (0..data.lights.len())
        .map(|k| {
            let (s, c) = gpu::input::light_channel(k);
            (0..samples)
                .map(|i| gpu::host::light_value(records[i].status, channels(s, i)[c]))
                .collect()
        })
        .collect();
    DataFile {
        records,
        lights,
        ..data.clone()
    }
}

/// Reads the slots the script saved for URL number `k`: (width, height, slots).
pub(super) fn read_slots(out: &Path, k: usize) -> (usize, usize, Vec<Vec<f32>>, serde_json::Value) {
    let meta: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join(format!("trace-{k}.json"))).unwrap())
            .unwrap();
    let (w, h) = (
        meta["width"].as_u64().unwrap() as usize,
        meta["height"].as_u64().unwrap() as usize,
    );
    let slots = (0..meta["slots"].as_u64().unwrap())
        .map(|s| {
            let bytes = std::fs::read(out.join(format!("trace-{k}-slot-{s}.f32"))).unwrap();
            assert_eq!(bytes.len(), w * h * SLOT * 4);
            bytes
                .chunks_exact(4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect()
        })
        .collect();
    (w, h, slots, meta)
}

/// Renders each case with the exact tracer and serves it; returns the data files' paths,
/// the servers and their URLs.
pub(super) fn render_and_serve(
    dir: &Path,
    cases: &[(&str, u32, u32)],
) -> (Vec<std::path::PathBuf>, Vec<Server>, Vec<String>) {
    let mut files = Vec::new();
    let (mut servers, mut urls) = (Vec::new(), Vec::new());
    for &(name, width, height) in cases {
        let scene = repo_root().join(format!("scenes/{name}.toml"));
        let (w, h) = (width.to_string(), height.to_string());
        let rendered = godel(&[
            "render",
            scene.to_str().unwrap(),
            "--method",
            "exact",
            "--width",
            &w,
            "--height",
            &h,
            "-q",
            "-o",
            dir.to_str().unwrap(),
        ]);
        assert!(rendered.status.success(), "{rendered:?}");
        let exr = dir.join(format!("{name}.exr"));
        let (server, url) = start_viewer(&exr, dir);
        files.push(exr);
        servers.push(server);
        urls.push(url);
    }
    (files, servers, urls)
}

#[test]
fn the_page_traces_example_scenes_on_the_gpu_as_the_exact_tracer_does_and_shades_them() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let (files, servers, urls) = render_and_serve(dir.path(), &CASES);
    let out = dir.path().join("browser");
    std::fs::create_dir(&out).unwrap();
    let mut args = urls[1..].to_vec();
    args.push("--shade".into());
    let seen = run_script("gpu-trace.mjs", &urls[0], &out, &args);
    drop(servers);
    assert_eq!(seen["console_errors"], serde_json::json!([]));
    let requests = seen["requests"].as_array().unwrap();
    for r in requests {
        let r = r.as_str().unwrap();
        assert!(
            urls.iter().any(|u| r.starts_with(u.as_str())),
            "the page asked for {r}"
        );
    }

    let mut failures = Vec::new();
    for (k, ((scene, _, _), file)) in CASES.iter().zip(&files).enumerate() {
        let data = DataFile::read(file).unwrap();
        let (w, h, slots, meta) = read_slots(&out, k);
        assert_eq!((w, h), (data.width, data.height), "{}", scene);
        let traced = traced_file(&data, &slots);
        let a = kernel_agreement::compare(scene, &traced, &data);
        eprintln!(
            "{a:?}; {w}×{h} samples traced in {:.0} ms (kernel compiled in {:.0} ms)",
            meta["traceMs"].as_f64().unwrap(),
            meta["compileMs"].as_f64().unwrap(),
        );
        assert!(a.seen > 100, "{scene}: the scene shows something");
        assert_compiled_as_the_host_compiles(scene, &data, &meta);
        assert!(
            meta["header"]
                .as_str()
                .unwrap()
                .contains("traced on the GPU in"),
            "{meta}"
        );
        if !data.lights.is_empty() && a.lit < 100 {
            failures.push(format!("{scene}: too few lit samples compared: {a:?}"));
        }
        if !a.holds() {
            failures.push(format!("{a:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert_shaded_as_a_files_frame(&out, &files[0]);

    // Without float render targets the page says why it cannot trace, and shows the file's
    // frame.
    let bare = &seen["without_float_targets"];
    let error = bare["error"].as_str().unwrap();
    assert!(
        error.contains("cannot trace on the GPU") && error.contains("EXT_color_buffer_float"),
        "{error}"
    );
    assert_eq!(bare["checked"], false);
    assert!(!bare["header"]
        .as_str()
        .unwrap()
        .contains("traced on the GPU"));
    assert!(bare["frames"].as_u64().unwrap() > 0);
}

/// The page compiled the kernel with the defines the server sent, and those are the ones
/// `godel render --gpu` compiles it with for the file's scene (crates/gpu/src/host.rs): the
/// same specialized source.
fn assert_compiled_as_the_host_compiles(name: &str, data: &DataFile, meta: &serde_json::Value) {
    let path = repo_root().join(format!("scenes/{name}.toml"));
    let scene = scene::Scene::from_str(&data.header.scene_text, path.to_str().unwrap()).unwrap();
    let buffers = meta["drawBuffers"].as_u64().unwrap() as usize;
    let defines = gpu::KernelInput::new(&scene).defines(buffers);
    assert_eq!(meta["defines"].as_str(), Some(defines.as_str()), "{name}");
    let source = meta["source"].as_str().unwrap();
    assert!(
        source == format!("#version 300 es\n{defines}{}", gpu::KERNEL),
        "{name}: the page compiled another source than #version, the defines and the kernel"
    );
}

/// The frame the script traced first and shaded with every layer on (`--shade`), against the
/// `shade` crate's picture of its records and the page's picture of the data file `file`.
fn assert_shaded_as_a_files_frame(out: &Path, file: &Path) {
    let data = DataFile::read(file).unwrap();
    let (w, h, slots, _) = read_slots(out, 0);
    let traced = traced_file(&data, &slots);
    let meta: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("trace-0-gpu.json")).unwrap()).unwrap();
    let settings: ShadeSettings = serde_json::from_value(meta["settings"].clone()).unwrap();
    assert_eq!(settings.shaders.len(), 4, "every layer is on");

    // The page's picture of the traced frame is the shade crate's picture of its records.
    let want = Shading::new(&traced, &settings).unwrap().image(&traced);
    let (pw, ph, gpu) = read_rgba(&out.join("trace-0-gpu.rgba"));
    assert_eq!((pw, ph), (data.width, data.height));
    let c = compare(&gpu, want.as_raw(), pw);
    assert!(
        c.max <= 1,
        "traced frame on the GPU vs shade: max {}, {:?}",
        c.max,
        c.off
    );

    // It shows the ball, lit, and differs from the file's frame only where the records do.
    let (_, _, file) = read_rgba(&out.join("trace-0-file.rgba"));
    let differ = compare(&gpu, &file, pw).off;
    let records_differ = (0..w * h)
        .filter(|&i| {
            let (a, b) = (&traced.records[i], &data.records[i]);
            a.status != b.status || a.object != b.object
        })
        .count();
    let hits = traced
        .records
        .iter()
        .filter(|r| r.status == RayStatus::Hit)
        .count();
    assert!(hits > 50, "{hits} hit samples");
    assert!(
        differ.len() <= records_differ + hits / 100,
        "{} pixels differ from the file's frame by more than a step; {records_differ} records do",
        differ.len()
    );
    let (cw, ch, canvas) = read_rgba(&out.join("trace-0-canvas.rgba"));
    let background = canvas[..3].to_vec();
    let lit = canvas
        .chunks_exact(3)
        .filter(|p| p.iter().zip(&background).any(|(a, b)| a.abs_diff(*b) > 40))
        .count();
    assert!(
        cw * ch > 0 && lit * 400 > cw * ch,
        "the canvas shows the traced ball: {lit} of {} pixels",
        cw * ch
    );
}
