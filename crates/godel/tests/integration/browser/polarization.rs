//! The page's polarization layer (issue 25; docs/physics.md, "Polarization") on the example
//! scene `polarization` (two balls whose light leaves polarized along a body axis, one at
//! rest, one in free fall, several images of each):
//!
//! - on the data file's frame, the page's ticks (texture and polarization layers) equal the
//!   picture `godel shade --shader texture,polarization` writes, within one 8-bit step;
//! - the page traces the frame on the GPU: its polarization channels agree with the exact
//!   tracer's within the kernel's tolerance (crates/gpu/tests/integration/common.rs), and its picture equals
//!   the `shade` crate's picture of the traced records within one step;
//! - dragging the first object's axis-azimuth slider re-shades at once: the axis in the
//!   settings turns to that azimuth, the ticks change (and equal the `shade` crate's for the
//!   new axis), and the page neither traces again nor asks the server for anything.

use super::gpu_trace::{kernel_agreement, read_slots, render_and_serve, traced_file};
use crate::browser_support::*;
use datafile::DataFile;
use shade::{ShadeSettings, Shading};

/// The azimuth (degrees) the test drags the first object's axis to: the scene's axis is
/// (1, 1, 0), at 45°.
const AZIMUTH: f64 = -60.0;

#[test]
fn the_pages_polarization_layer_equals_godel_shade_and_its_axis_control_reshades_only() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let (files, servers, urls) = render_and_serve(dir.path(), &[("polarization", 240, 80)]);
    let (exr, url) = (&files[0], &urls[0]);
    let data = DataFile::read(exr).unwrap();
    let cli_png = dir.path().join("cli.png");
    let shaded = godel(&[
        "shade",
        exr.to_str().unwrap(),
        "--shader",
        "texture,polarization",
        "-o",
        cli_png.to_str().unwrap(),
    ]);
    assert!(shaded.status.success(), "{shaded:?}");

    let out = dir.path().join("browser");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script("polarization.mjs", url, &out, &[AZIMUTH.to_string()]);
    drop(servers);
    assert_eq!(seen["console_errors"], serde_json::json!([]));
    assert_only_local_requests(&seen, url);
    let settings_of = |name: &str| -> ShadeSettings {
        let meta: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join(format!("{name}.json"))).unwrap())
                .unwrap();
        serde_json::from_value(meta["settings"].clone()).unwrap()
    };

    // The file's frame against `godel shade`'s picture.
    let (w, h, file) = read_rgba(&out.join("file.rgba"));
    assert_eq!((w, h), data.picture_size());
    let cli = image::open(&cli_png).unwrap().to_rgb8();
    let c = compare(&file, cli.as_raw(), w);
    assert!(c.max <= 1, "file frame vs godel shade: {:?}", c.off);
    let plain = Shading::new(
        &data,
        &ShadeSettings {
            shaders: vec![shade::ShaderKind::Texture],
            ..settings_of("file")
        },
    )
    .unwrap()
    .image(&data);
    let ticks = compare(cli.as_raw(), plain.as_raw(), w).off.len();
    assert!(ticks > 300, "the ticks cover {ticks} pixels");

    // The frame traced in the page: its channels, and its picture.
    let (tw, th, slots, _) = read_slots(&out, 0);
    assert_eq!((tw, th), (data.width, data.height));
    let traced = traced_file(&data, &slots);
    let a = kernel_agreement::compare("polarization", &traced, &data);
    eprintln!("traced in the page against the exact tracer: {a:?}");
    assert!(a.seen > 1000 && a.holds(), "{a:?}");
    let shade_traced = |name: &str| {
        let (_, _, page) = read_rgba(&out.join(format!("{name}.rgba")));
        let settings = settings_of(name);
        let want = Shading::new(&traced, &settings).unwrap().image(&traced);
        let c = compare(&page, want.as_raw(), w);
        assert!(c.max <= 1, "{name}: page vs shade: {:?}", c.off);
        (page, settings)
    };
    let (before, _) = shade_traced("traced");
    let (after, turned) = shade_traced("turned");

    // The slider turned the first object's axis, and only that: re-shaded, not re-traced.
    let first = &data.header.object_names[0];
    let axis = turned.objects[first].polarization.unwrap();
    let azimuth = axis[1].atan2(axis[0]).to_degrees();
    assert!(
        (azimuth - AZIMUTH).abs() < 1e-9 && axis[2].abs() < 1e-9,
        "{axis:?}"
    );
    let changed = compare(&before, &after, w).off.len();
    assert!(changed > 40, "turning the axis changed {changed} pixels");
    assert_eq!(seen["requests_while_turning"], serde_json::json!([]));
    assert!(seen["traces_before"].is_number());
    assert_eq!(seen["traces_before"], seen["traces_after"]);
}
