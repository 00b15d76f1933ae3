//! Every layer combination, shaded on the GPU in the browser, against the `shade` crate
//! (what `godel shade` and "Save PNG" make): within one 8-bit step per channel. The only
//! pixels excused are those whose texture coordinate lies within 1e-4 of a checker cell's
//! edge, where the GPU's f32 arithmetic may pick the neighbouring cell (the CPU computes the
//! coordinate in f64); the test counts them and requires them to be rare. The same holds for
//! an anti-aliased file (every sample shaded, then box-filtered). The cases include exposure
//! compensation (`ev`), the overlay layer (orientation marks, legend, square labels) that
//! the page fetches from the server and composites over its shading, and the polarization
//! layer (issue 25): its ticks, drawn by the page from the file's pol and dir channels and
//! each object's axis, equal the crate's on every pixel within one step.

use crate::browser_support::*;
use datafile::DataFile;
use shade::{BrightnessMode, ShadeSettings, ShaderKind, Shading, TextureChoice, TimeMode};

/// A 240×60 panorama of a checkered ball lit from the side and a falling ball painted with an
/// image file, in Gödel's universe: varied u, v, g, t_emit, cos_i and light.
fn scene(texture: &std::path::Path) -> String {
    format!(
        r#"
name = "layers"
[spacetime]
metric = "godel"
a = 1.0
[observer]
time = 0.0
position = {{ r = 0.0, phi = 0.0, z = 0.0 }}
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "panorama"
h_fov_deg = 240.0
v_fov_deg = 40.0
width = 240
height = 60
[trace]
method = "numeric"
max_past = 8.0
[[object]]
name = "ball"
radius = 0.25
texture = {{ kind = "checker", rows = 8, cols = 16 }}
temperature = 5800.0
motion = {{ kind = "rest", position = {{ x = 1.0, y = 0.0, z = 0.0 }} }}
[[object]]
name = "globe"
radius = 0.2
texture = {{ kind = "image", path = "{}" }}
temperature = 3500.0
motion = {{ kind = "geodesic", time = 0.0, position = {{ x = 0.8, y = 0.5, z = 0.1 }}, speed = 0.5, direction = [0, -1, 0] }}
[[light]]
position = {{ x = 1.0, y = 1.0, z = 0.0 }}
color = [1.0, 0.9, 0.8]
power = 12.0
"#,
        texture.display()
    )
}

/// A 37×19 image with colour ramps and a few sharp spots (odd sizes: no lucky alignment).
fn write_texture(path: &std::path::Path) {
    let img = image::RgbImage::from_fn(37, 19, |x, y| {
        let spot = (x * 7 + y * 3) % 11 == 0;
        image::Rgb([
            (x * 255 / 36) as u8,
            if spot { 255 } else { (y * 255 / 18) as u8 },
            ((x + y) * 97 % 256) as u8,
        ])
    });
    img.save(path).unwrap();
}

/// The settings tried: each of the 15 layer combinations, then the other controls.
fn cases(data: &DataFile) -> Vec<ShadeSettings> {
    let defaults = ShadeSettings::defaults_for(data);
    let with = |change: &dyn Fn(&mut ShadeSettings)| {
        let mut s = defaults.clone();
        change(&mut s);
        s
    };
    let mut cases: Vec<ShadeSettings> = (1..16u32)
        .map(|mask| {
            with(&|s| {
                s.shaders = ShaderKind::ALL
                    .into_iter()
                    .enumerate()
                    .filter(|(i, _)| mask & (1 << i) != 0)
                    .map(|(_, k)| k)
                    .collect()
            })
        })
        .collect();
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Time, ShaderKind::Frequency];
        s.time.mode = TimeMode::Travel;
        s.time.travel_min = 0.5;
        s.time.travel_max = 6.25;
    }));
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Frequency];
        s.brightness = BrightnessMode::Physical;
        s.exposure = 1.7;
        s.objects.get_mut("globe").unwrap().temperature = 1200.0;
    }));
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Frequency, ShaderKind::Light];
        s.brightness = BrightnessMode::Physical;
        s.exposure = 0.3;
        s.reference_squares = false;
    }));
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Texture];
        let ball = s.objects.get_mut("ball").unwrap();
        ball.texture = TextureChoice::Earth;
        ball.offset_u = 0.123;
        ball.offset_v = -0.05;
        ball.rotation_deg = 33.0;
        s.objects.get_mut("globe").unwrap().texture = TextureChoice::Gradient;
    }));
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Texture, ShaderKind::Time];
        s.objects.get_mut("ball").unwrap().window_texture =
            TextureChoice::Checker { rows: 3, cols: 5 };
        s.objects.get_mut("globe").unwrap().texture = TextureChoice::Uniform {
            color: [0.2, 0.5, 0.9],
        };
        s.time.t0 = -3.0;
        s.time.dt = 1.5;
    }));
    // Exposure compensation (ev): hit colours scaled by 2^ev before the tone curve, the
    // reference squares too; a page that ignored ev would show the ev = 0 picture.
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Texture, ShaderKind::Light];
        s.ev = 1.5;
    }));
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Frequency];
        s.ev = -2.3;
    }));
    // The server's overlay layer composited by the page: orientation marks over the
    // texture layer; marks, reference squares with their labels and the travel-time
    // legend together.
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Texture];
        s.grid = true;
    }));
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Time, ShaderKind::Frequency];
        s.time.mode = TimeMode::Travel;
        s.grid = true;
        s.ev = 0.7;
    }));
    // The polarization layer: alone (over the texture layer), over the frequency and light
    // layers, and with one object polarized only; the axes in the objects' body axes.
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Polarization];
        s.objects.get_mut("ball").unwrap().polarization = Some([1.0, 1.0, 0.0]);
        s.objects.get_mut("globe").unwrap().polarization = Some([0.0, 0.0, 2.0]);
    }));
    cases.push(with(&|s| {
        s.shaders = vec![
            ShaderKind::Frequency,
            ShaderKind::Light,
            ShaderKind::Polarization,
        ];
        s.objects.get_mut("ball").unwrap().polarization = Some([0.2, -1.0, 0.7]);
        s.objects.get_mut("globe").unwrap().polarization = Some([1.0, 0.0, 0.0]);
    }));
    cases.push(with(&|s| {
        s.shaders = vec![
            ShaderKind::Texture,
            ShaderKind::Time,
            ShaderKind::Polarization,
        ];
        s.objects.get_mut("globe").unwrap().polarization = Some([0.3, 0.4, -0.5]);
    }));
    cases.push(with(&|s| {
        s.shaders = vec![ShaderKind::Light];
        s.light.ambient = 0.4;
        s.light.sources[0].intensity = 2.5;
        s.light.sources[0].color = [0.3, 1.0, 0.5];
    }));
    cases
}

/// Whether any sample of picture pixel (`col`, `row`) lies near a checker edge (see
/// [`near_checker_edge`]).
fn pixel_near_checker_edge(
    data: &DataFile,
    settings: &ShadeSettings,
    col: usize,
    row: usize,
) -> bool {
    data.sample_indices(col, row)
        .any(|i| near_checker_edge(data, settings, i))
}

/// Whether pixel `i`'s texture coordinates lie within 1e-4 of a cell edge of a checker that
/// object's textures use under `settings` (computed in f64 as the `shade` crate does).
fn near_checker_edge(data: &DataFile, settings: &ShadeSettings, i: usize) -> bool {
    let r = &data.records[i];
    let Some(name) = usize::try_from(r.object)
        .ok()
        .and_then(|k| data.header.object_names.get(k))
    else {
        return false;
    };
    let o = &settings.objects[name];
    let u = o.scale_u * f64::from(r.u) + o.offset_u - o.rotation_deg / 360.0;
    let v = o.scale_v * f64::from(r.v) + o.offset_v;
    let (u, v) = (u - u.floor(), v.clamp(0.0, 1.0));
    let edge = |x: f64| (x - x.round()).abs() < 1e-4;
    // The scene's checker (the ball's), and any checker chosen in the settings.
    let mut grids = vec![(8u32, 16u32)];
    for t in [&o.texture, &o.window_texture] {
        if let TextureChoice::Checker { rows, cols } = t {
            grids.push((*rows, *cols));
        }
    }
    grids.iter().any(|&(rows, cols)| {
        edge(u * f64::from(cols)) || edge(v * f64::from(rows)) || edge(u * 2.0) || edge(v * 2.0)
    })
}

#[test]
fn every_layer_combination_on_the_gpu_equals_the_shade_crate() {
    check_layers(240, 60, 1);
}

/// The scene with 2×2 samples per pixel at half the size (the same rays): the page opens the
/// file of 240×60 samples as a 120×30 picture, shades every sample and box-filters them in
/// linear light, as `godel shade` does.
#[test]
fn an_anti_aliased_file_on_the_gpu_equals_the_shade_crate() {
    check_layers(120, 30, 2);
}

/// Renders [`scene`] at `width` × `height` pixels with s×s rays per pixel, shades it in the
/// browser with every case and compares each picture with the `shade` crate's.
fn check_layers(width: usize, height: usize, s: usize) {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let texture = dir.path().join("pattern.png");
    write_texture(&texture);
    let text = scene(&texture).replace(
        "width = 240\nheight = 60\n",
        &format!("width = {width}\nheight = {height}\nsamples = {}\n", s * s),
    );
    let exr = render(dir.path(), "layers", &text);
    let data = DataFile::read(&exr).unwrap();
    assert_eq!(data.picture_size(), (width, height));
    assert_eq!((data.width, data.height), (width * s, height * s));
    assert!(!data.lights.is_empty());
    let objects_seen = |k: i32| data.records.iter().filter(|r| r.object == k).count();
    assert!(
        objects_seen(0) > 200 && objects_seen(1) > 20,
        "both balls show"
    );

    let cases = cases(&data);
    let cases_file = dir.path().join("cases.json");
    std::fs::write(&cases_file, serde_json::to_vec(&cases).unwrap()).unwrap();
    let (server, url) = start_viewer(&exr, dir.path());
    let out = dir.path().join("browser");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script(
        "layers.mjs",
        &url,
        &out,
        &[cases_file.display().to_string()],
    );
    drop(server);

    // The ev cases differ from their ev = 0 pictures: comparing within one step means
    // something there.
    for (k, settings) in cases.iter().enumerate().filter(|(_, s)| s.ev != 0.0) {
        let plain = ShadeSettings {
            ev: 0.0,
            ..settings.clone()
        };
        let a = Shading::new(&data, settings).unwrap().image(&data);
        let b = Shading::new(&data, &plain).unwrap().image(&data);
        let c = compare(a.as_raw(), b.as_raw(), width);
        assert!(
            c.off.len() > 50,
            "case {k}: ev changes {} pixels",
            c.off.len()
        );
    }

    // The overlay cases differ from their pictures without overlays (marks, legend, labels
    // drawn): the page must composite the layer to pass.
    let drawn = |s: &ShadeSettings| {
        s.grid
            || (s.shaders.contains(&ShaderKind::Time)
                && s.time.mode == TimeMode::Travel
                && s.time.legend)
            || (s.shaders.contains(&ShaderKind::Frequency) && s.reference_squares)
    };
    for (k, settings) in cases.iter().enumerate().filter(|(_, s)| s.grid) {
        let mut bare = settings.clone();
        bare.grid = false;
        bare.time.legend = false;
        bare.reference_squares = false;
        assert!(!drawn(&bare));
        let a = Shading::new(&data, settings).unwrap().image(&data);
        let b = Shading::new(&data, &bare).unwrap().image(&data);
        let c = compare(a.as_raw(), b.as_raw(), width);
        assert!(
            c.off.len() > 200,
            "case {k}: overlays change {} pixels",
            c.off.len()
        );
    }

    // The polarization cases draw ticks: the page must draw them to pass.
    let mut ticked = 0;
    for (k, settings) in
        (cases.iter().enumerate()).filter(|(_, s)| s.shaders.contains(&ShaderKind::Polarization))
    {
        let mut bare = settings.clone();
        bare.objects
            .values_mut()
            .for_each(|o| o.polarization = None);
        let a = Shading::new(&data, settings).unwrap().image(&data);
        let b = Shading::new(&data, &bare).unwrap().image(&data);
        let c = compare(a.as_raw(), b.as_raw(), width);
        assert!(
            c.off.len() * 200 > width * height,
            "case {k}: ticks change {} pixels",
            c.off.len()
        );
        ticked += 1;
    }
    assert_eq!(ticked, 3);

    let (mut worst, mut worst_excused, mut excused) = (0, 0, 0);
    for (k, settings) in cases.iter().enumerate() {
        assert_eq!(seen["errors"][k], serde_json::Value::Null, "case {k}");
        let cpu = Shading::new(&data, settings).unwrap().image(&data);
        let (w, h, gpu) = read_rgba(&out.join(format!("case-{k}.rgba")));
        assert_eq!((w, h), (width, height));
        let c = compare(&gpu, cpu.as_raw(), w);
        for &(col, row) in &c.off {
            assert!(
                pixel_near_checker_edge(&data, settings, col, row),
                "case {k} ({:?}): pixel ({col}, {row}) differs by more than one step: GPU {:?}, \
                 CPU {:?}",
                settings.shaders,
                &gpu[(row * w + col) * 3..][..3],
                cpu.get_pixel(col as u32, row as u32)
            );
        }
        excused += c.off.len();
        worst = worst.max(c.within);
        worst_excused = worst_excused.max(c.max);
    }
    // Figures for the report.
    eprintln!(
        "GPU vs shade over {} cases ({}×{} pixels, {} samples each): max difference {worst} \
         (8-bit steps) outside {excused} pixels excused at checker edges (where it is \
         {worst_excused}), of {} shaded",
        cases.len(),
        width,
        height,
        data.supersample().pow(2),
        cases.len() * width * height
    );
    assert!(excused * 1000 <= cases.len() * width * height);
    assert!(seen["console_errors"].as_array().unwrap().is_empty());
    assert_only_local_requests(&seen, &url);
}
