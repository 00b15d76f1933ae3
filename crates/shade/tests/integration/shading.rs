//! Tests of the prepared shader [`shade::Shading`]: the texture layer reproduces the render's
//! preview, the frequency layer obeys the shift law and makes 6504 K white, the time window
//! is decided by t_emit alone, the light layer follows its formula, textures move and lamps
//! blink, and bad settings are refused naming the field.

use datafile::record::{PixelRecord, RayStatus};
use datafile::{DataFile, DataHeader};
use scene::Scene;
use shade::blackbody::{normalize_max, observed_xyz, unit_rgb};
use shade::colour::rgb_to_srgb8;
use shade::{
    BrightnessMode, Lamp, LightSource, ShadeError, ShadeSettings, ShaderKind, Shading,
    TextureChoice, TimeMode, MAX_LAMPS, MAX_LIGHT_SOURCES,
};
use testkit::hit;

/// Two objects: a checkered ball at 4000 K and a moon with a gradient.
fn scene() -> String {
    format!(
        "name = \"two\"\n{}{}{}",
        testkit::panorama(220.0, 25.0, 64, 8),
        testkit::textured_ball_at("ball", 0.1, &testkit::checker(4, 8), 4000.0, 1.0, 0.0),
        r#"[[object]]
name = "moon"
radius = 0.1
texture = { kind = "gradient" }
motion = { kind = "rest", position = { r = 1.0, phi = 1.0, z = 0.0 } }
"#
    )
}

fn header() -> DataHeader {
    testkit::godel_header("two", &scene(), "panorama", &["ball", "moon"])
}

/// 64×8 pixels: both objects at many (u, v, cos_i), a few misses and failures.
fn synthetic() -> DataFile {
    let (w, h) = (64usize, 8usize);
    let records = (0..w * h)
        .map(|i| {
            let (c, r) = (i % w, i / w);
            match c % 16 {
                15 => PixelRecord::MISS,
                14 if r == 0 => PixelRecord::miss(RayStatus::Failed),
                _ => hit(
                    (r % 2) as i32,
                    (c as f32 + 0.37) / w as f32,
                    (r as f32 + 0.5) / h as f32,
                    0.5 + c as f32 / 32.0,
                    -(c as f32) / 4.0,
                    (c as f32 / 40.0) - 0.2,
                ),
            }
        })
        .collect();
    DataFile {
        header: header(),
        width: w,
        height: h,
        records,
        lights: vec![],
        polarization: false,
    }
}

fn one_pixel(rec: PixelRecord, lights: Vec<f32>) -> DataFile {
    DataFile {
        header: header(),
        width: 1,
        height: 1,
        records: vec![rec],
        lights: lights.into_iter().map(|l| vec![l]).collect(),
        polarization: false,
    }
}

fn with(data: &DataFile, f: impl FnOnce(&mut ShadeSettings)) -> ShadeSettings {
    let mut s = ShadeSettings::defaults_for(data);
    f(&mut s);
    s
}

/// The default settings of `data` with the layers `shaders`.
fn with_shaders(data: &DataFile, shaders: &[ShaderKind]) -> ShadeSettings {
    with(data, |s| s.shaders = shaders.to_vec())
}

fn close(a: [f32; 3], b: [f32; 3], tol: f32) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

#[test]
fn texture_layer_with_the_scenes_textures_reproduces_the_preview() {
    let data = synthetic();
    let scene = Scene::from_str(&scene(), "two.toml").unwrap();
    let preview = shade::preview(&data, &scene).unwrap();
    let shaded = Shading::new(&data, &ShadeSettings::defaults_for(&data))
        .unwrap()
        .image(&data);
    assert_eq!(shaded.dimensions(), preview.dimensions());
    for (a, b) in shaded.pixels().zip(preview.pixels()) {
        for k in 0..3 {
            assert!(a[k].abs_diff(b[k]) <= 1, "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn a_6504_kelvin_black_body_comes_out_near_white() {
    let data = one_pixel(hit(0, 0.5, 0.5, 1.0, -1.0, 1.0), vec![]);
    let s = with(&data, |s| {
        s.shaders = vec![ShaderKind::Frequency];
        s.objects.get_mut("ball").unwrap().temperature = 6504.0;
    });
    let c = Shading::new(&data, &s).unwrap().pixel(&data, 0);
    let px = rgb_to_srgb8(c);
    assert!(px.iter().all(|&v| v >= 240), "{px:?}");
}

#[test]
fn frequency_layer_obeys_the_shift_law_and_the_spectrum() {
    for &(g, t) in &[
        (0.5f32, 6000.0),
        (1.7, 3000.0),
        (2.3, 9000.0),
        (0.8, 4500.0),
    ] {
        let data = one_pixel(hit(0, 0.5, 0.5, g, -1.0, 1.0), vec![]);
        let shifted = with(&data, |s| {
            s.shaders = vec![ShaderKind::Frequency];
            s.objects.get_mut("ball").unwrap().temperature = t;
        });
        let a = Shading::new(&data, &shifted).unwrap().pixel(&data, 0);
        let unshifted_data = one_pixel(hit(0, 0.5, 0.5, 1.0, -1.0, 1.0), vec![]);
        let direct = with(&unshifted_data, |s| {
            s.shaders = vec![ShaderKind::Frequency];
            s.objects.get_mut("ball").unwrap().temperature = f64::from(g) * t;
        });
        let b = Shading::new(&unshifted_data, &direct)
            .unwrap()
            .pixel(&unshifted_data, 0);
        assert!(close(a, b, 1e-6), "g = {g}, T = {t}: {a:?} vs {b:?}");
        // Independently: the observed spectrum g³B_ν(ν/g, T) integrated against CIE 1931.
        let expect = normalize_max(unit_rgb(observed_xyz(f64::from(g), t))).map(|c| c as f32);
        assert!(close(a, expect, 2e-3), "g = {g}: {a:?} vs {expect:?}");
    }
}

#[test]
fn physical_brightness_scales_with_the_exposure() {
    let data = one_pixel(hit(0, 0.5, 0.5, 0.7, -1.0, 1.0), vec![]);
    let at = |e: f64| {
        let s = with(&data, |s| {
            s.shaders = vec![ShaderKind::Frequency];
            s.brightness = BrightnessMode::Physical;
            s.exposure = e;
        });
        Shading::new(&data, &s).unwrap().pixel(&data, 0)
    };
    let (a, b) = (at(0.1), at(0.2));
    assert!(a[0] > 0.0);
    assert!(close(b, a.map(|c| 2.0 * c), 1e-5), "{a:?} {b:?}");
}

#[test]
fn time_window_is_decided_by_t_emit_alone() {
    let red = [1.0, 0.0, 0.0];
    let blue = [0.0, 0.0, 1.0];
    // Same u, v, g, cos_i everywhere; only t_emit differs.
    let ts = [-9.0f32, -5.0001, -5.0, -4.0, -3.0, -2.9999, 0.0];
    let records = ts.iter().map(|&t| hit(0, 0.3, 0.3, 1.2, t, 1.0)).collect();
    let data = DataFile {
        header: header(),
        width: ts.len(),
        height: 1,
        records,
        lights: vec![],
        polarization: false,
    };
    let s = with(&data, |s| {
        s.shaders = vec![ShaderKind::Time];
        s.time.mode = TimeMode::Window;
        s.time.t0 = -5.0;
        s.time.dt = 2.0;
        let o = s.objects.get_mut("ball").unwrap();
        o.texture = TextureChoice::Uniform { color: blue };
        o.window_texture = TextureChoice::Uniform { color: red };
    });
    let shading = Shading::new(&data, &s).unwrap();
    for (i, &t) in ts.iter().enumerate() {
        let inside = (-5.0..=-3.0).contains(&t);
        let expect = if inside { red } else { blue }.map(|c| c as f32);
        assert_eq!(shading.pixel(&data, i), expect, "t_emit = {t}");
    }
}

#[test]
fn frequency_times_time_window_is_the_product() {
    let data = one_pixel(hit(0, 0.3, 0.3, 1.3, -4.0, 0.5), vec![]);
    let freq = with_shaders(&data, &[ShaderKind::Frequency]);
    let window = with(&data, |s| {
        s.shaders = vec![ShaderKind::Time];
        s.time.t0 = -5.0;
        s.time.dt = 2.0;
        s.objects.get_mut("ball").unwrap().window_texture = TextureChoice::Uniform {
            color: [0.5, 1.0, 0.25],
        };
    });
    let mut both = window.clone();
    both.shaders = vec![ShaderKind::Frequency, ShaderKind::Time];
    let f = Shading::new(&data, &freq).unwrap().pixel(&data, 0);
    let b = Shading::new(&data, &both).unwrap().pixel(&data, 0);
    // The window texture, painted on the body: Lambert factor 0.25 + 0.75·cos_i.
    let lambert = 0.25 + 0.75 * 0.5;
    let expect = [f[0] * 0.5 * lambert, f[1] * lambert, f[2] * 0.25 * lambert];
    assert!(close(b, expect, 1e-6), "{b:?} vs {expect:?}");
}

#[test]
fn light_layer_is_albedo_times_ambient_plus_lights() {
    let albedo = [0.8, 0.6, 0.4];
    let data = one_pixel(hit(0, 0.3, 0.3, 1.0, -1.0, 0.2), vec![0.5, 2.0]);
    let base = with(&data, |s| {
        s.shaders = vec![ShaderKind::Light];
        s.light.ambient = 0.1;
        s.light.sources[0].color = [1.0, 0.5, 0.0];
        s.light.sources[1].intensity = 0.25;
        s.objects.get_mut("ball").unwrap().texture = TextureChoice::Uniform { color: albedo };
    });
    let c = Shading::new(&data, &base).unwrap().pixel(&data, 0);
    let lit = [
        0.1 + 0.5 * 1.0 + 0.25 * 2.0,
        0.1 + 0.5 * 0.5 + 0.25 * 2.0,
        0.1 + 0.0 + 0.25 * 2.0,
    ];
    let expect = [0, 1, 2].map(|k| (albedo[k] * lit[k]) as f32);
    assert!(close(c, expect, 1e-6), "{c:?} vs {expect:?}");
    // Light 0 off.
    let mut off = base.clone();
    off.light.sources[0].on = false;
    let c = Shading::new(&data, &off).unwrap().pixel(&data, 0);
    let expect = [0, 1, 2].map(|k| (albedo[k] * (0.1 + 0.5)) as f32);
    assert!(close(c, expect, 1e-6), "{c:?} vs {expect:?}");
}

#[test]
fn light_layer_without_light_channels_is_an_error() {
    let data = synthetic();
    let s = with_shaders(&data, &[ShaderKind::Texture, ShaderKind::Light]);
    let e = Shading::new(&data, &s).unwrap_err();
    assert!(matches!(e, ShadeError::NoLightChannels), "{e}");
    assert!(e.to_string().contains("light channels"), "{e}");
}

#[test]
fn turning_the_body_moves_the_texture() {
    let data = synthetic();
    let plain = Shading::new(&data, &ShadeSettings::defaults_for(&data))
        .unwrap()
        .image(&data);
    // A full turn changes nothing visible.
    let full = with(&data, |s| {
        s.objects.get_mut("ball").unwrap().rotation_deg = 360.0;
    });
    let turned = Shading::new(&data, &full).unwrap().image(&data);
    for (a, b) in plain.pixels().zip(turned.pixels()) {
        for k in 0..3 {
            assert!(a[k].abs_diff(b[k]) <= 1);
        }
    }
    // Turning by one checker column (8 columns: 45°) equals sampling at u − 1/8.
    let one_pixel_data = one_pixel(hit(0, 0.3, 0.3, 1.0, -1.0, 1.0), vec![]);
    let moved = |deg: f64, offset: f64, u: f32| {
        let d = one_pixel(hit(0, u, 0.3, 1.0, -1.0, 1.0), vec![]);
        let s = with(&one_pixel_data, |s| {
            let o = s.objects.get_mut("ball").unwrap();
            o.rotation_deg = deg;
            o.offset_u = offset;
        });
        Shading::new(&d, &s).unwrap().pixel(&d, 0)
    };
    assert_eq!(moved(45.0, 0.0, 0.3), moved(0.0, 0.0, 0.3 - 0.125));
    assert_ne!(moved(45.0, 0.0, 0.3), moved(0.0, 0.0, 0.3));
    assert_eq!(moved(0.0, 0.125, 0.3), moved(0.0, 0.0, 0.425));
}

/// A green lamp at (0.3, 0.5), 10° wide, on for the first quarter of every 2 time units.
fn green_lamp() -> Lamp {
    Lamp {
        u: 0.3,
        v: 0.5,
        radius_deg: 10.0,
        period: 2.0,
        phase: 0.0,
        duty: 0.25,
        color: [0.0, 1.0, 0.0],
    }
}

#[test]
fn lamps_blink_with_the_emission_time() {
    let lamp = green_lamp();
    let at = |u: f32, t: f32| {
        let d = one_pixel(hit(0, u, 0.5, 1.0, t, 1.0), vec![]);
        let s = with(&d, |s| {
            s.objects.get_mut("ball").unwrap().lamps = vec![lamp.clone()]
        });
        Shading::new(&d, &s).unwrap().pixel(&d, 0)
    };
    // On during [0, 0.5) of each 2-unit period of coordinate time t = observer time + t_emit.
    assert_eq!(at(0.3, -4.0)[1], 1.0);
    assert_eq!(at(0.3, -1.7)[1], 1.0);
    assert!((at(0.3, -1.0)[1] - 0.1).abs() < 1e-6);
    assert!((at(0.3, -0.5)[1] - 0.1).abs() < 1e-6);
    // Outside its 10° disc the texture shows, whatever the time.
    assert_eq!(at(0.5, -4.0), at(0.5, -1.0));
}

/// The caps on per-settings sizes (lamps per object, light sources) hold for every front end:
/// one over is refused naming the field and the cap, the cap itself is accepted.
#[test]
fn lamps_and_light_sources_are_capped() {
    let data = synthetic();
    let lamp = green_lamp();
    let lamps = |n: usize| {
        with(&data, |s| {
            s.objects.get_mut("moon").unwrap().lamps = vec![lamp.clone(); n]
        })
    };
    assert!(Shading::new(&data, &lamps(MAX_LAMPS)).is_ok());
    let e = Shading::new(&data, &lamps(MAX_LAMPS + 1)).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "shade settings: objects.moon.lamps: at most {MAX_LAMPS} lamps per object, got {}",
            MAX_LAMPS + 1
        )
    );

    let source = LightSource {
        on: true,
        intensity: 1.0,
        color: [1.0; 3],
    };
    let sources = |n: usize| with(&data, |s| s.light.sources = vec![source.clone(); n]);
    // Listed sources beyond the data file's (none) are ignored up to the cap.
    assert!(Shading::new(&data, &sources(MAX_LIGHT_SOURCES)).is_ok());
    let e = Shading::new(&data, &sources(20_000)).unwrap_err();
    assert!(
        e.to_string().starts_with(&format!(
            "shade settings: light.sources: at most {MAX_LIGHT_SOURCES} sources"
        )),
        "{e}"
    );
}

/// A change of the settings and the field its error must name.
type BadSetting = (Box<dyn Fn(&mut ShadeSettings)>, &'static str);

#[test]
fn bad_settings_are_refused_naming_the_field() {
    let data = synthetic();
    let cases: Vec<BadSetting> = vec![
        (
            Box::new(|s| s.objects.get_mut("ball").unwrap().temperature = -5.0),
            "objects.ball.temperature",
        ),
        (
            Box::new(|s| s.objects.get_mut("moon").unwrap().scale_u = f64::NAN),
            "objects.moon.scale_u",
        ),
        (Box::new(|s| s.time.dt = 0.0), "time.dt"),
        (Box::new(|s| s.exposure = f64::INFINITY), "exposure"),
        (Box::new(|s| s.shaders.clear()), "shaders"),
        (
            Box::new(|s| {
                let o = s.objects["ball"].clone();
                s.objects.insert("sun".into(), o);
            }),
            "objects.sun",
        ),
        (
            Box::new(|s| {
                s.objects.get_mut("ball").unwrap().texture =
                    TextureChoice::Checker { rows: 0, cols: 2 }
            }),
            "objects.ball.texture",
        ),
    ];
    for (change, field) in cases {
        let s = with(&data, change);
        let e = Shading::new(&data, &s).unwrap_err();
        assert!(
            e.to_string().contains(&format!("{field}:")),
            "expected {field}: {e}"
        );
    }
    let s = with(&data, |s| {
        s.objects.get_mut("ball").unwrap().texture = TextureChoice::Image {
            path: "/nonexistent/map.png".into(),
        }
    });
    let e = Shading::new(&data, &s).unwrap_err();
    assert!(e.to_string().contains("/nonexistent/map.png"), "{e}");
}

#[test]
fn travel_time_false_colour_runs_over_its_range_with_a_legend() {
    let data = synthetic();
    let s = with(&data, |s| {
        s.shaders = vec![ShaderKind::Time];
        s.time.mode = TimeMode::Travel;
        s.time.travel_min = 0.0;
        s.time.travel_max = 16.0;
        s.time.legend = false;
    });
    let shading = Shading::new(&data, &s).unwrap();
    // Column c has travel time c/4: ends of the range get the map's ends.
    let first = shading.pixel(&data, 0);
    let last = shading.pixel(&data, 64 * 2 + 63 - 1);
    assert!(first[2] > first[1], "violet at the short end: {first:?}");
    assert!(last[0] > last[2], "yellow toward the long end: {last:?}");
    let mut img_without = Vec::new();
    shading.image_into(&data, &mut img_without);
    let mut with_legend = s.clone();
    with_legend.time.legend = true;
    let mut img_with = Vec::new();
    Shading::new(&data, &with_legend)
        .unwrap()
        .image_into(&data, &mut img_with);
    assert_eq!(img_with.len(), 64 * 8 * 3);
    // Too small for a legend (under 48×24): unchanged.
    assert_eq!(img_with, img_without);
}

#[test]
fn image_does_not_depend_on_the_thread_count() {
    let data = synthetic();
    let s = with_shaders(&data, &[ShaderKind::Frequency, ShaderKind::Texture]);
    let shading = Shading::new(&data, &s).unwrap();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| shading.image(&data));
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
        .install(|| shading.image(&data));
    assert_eq!(one, two);
}
