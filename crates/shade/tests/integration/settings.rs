//! Tests of the settings API: defaults from a data file, TOML round trips, overlays with
//! located errors, and keyframe text that pastes into a script.

use std::path::Path;

use datafile::DataFile;
use shade::{
    keyframe_toml, Script, ShadeError, ShadeSettings, ShaderKind, TextureChoice, TimeMode,
};

/// A checkered ball at 4000 K, a moon and a coloured light.
fn scene() -> String {
    format!(
        "name = \"two\"\n[camera]\nkind = \"panorama\"\n{}{}{}",
        testkit::textured_ball_at("ball", 0.1, &testkit::checker(4, 8), 4000.0, 1.0, 0.0),
        testkit::ball_at_rest("moon", 0.1, 1.0, 1.0),
        "[[light]]\nposition = { r = 1.5, phi = 0.0, z = 0.0 }\ncolor = [1.0, 0.5, 0.25]\n",
    )
}

fn data(lights: usize) -> DataFile {
    let (w, h) = (8, 2);
    let records = (0..w * h)
        .map(|i| testkit::hit((i % 2) as i32, 0.3, 0.6, 1.0, -2.5 - i as f32 * 0.5, 1.0))
        .collect();
    DataFile {
        header: testkit::godel_header("two", &scene(), "panorama", &["ball", "moon"]),
        width: w,
        height: h,
        records,
        lights: vec![vec![0.5; w * h]; lights],
        polarization: false,
    }
}

#[test]
fn defaults_come_from_the_embedded_scene() {
    let s = ShadeSettings::defaults_for(&data(1));
    assert_eq!(s.shaders, vec![ShaderKind::Texture]);
    assert_eq!(s.objects["ball"].temperature, 4000.0);
    assert_eq!(s.objects["moon"].temperature, 5800.0);
    assert_eq!(s.objects["ball"].texture, TextureChoice::Scene);
    assert_eq!(s.light.sources.len(), 1);
    assert_eq!(s.light.sources[0].color, [1.0, 0.5, 0.25]);
    // Travel times seen are 2.5 .. 10: the range is rounded out to whole units.
    assert_eq!((s.time.travel_min, s.time.travel_max), (2.0, 10.0));
}

#[test]
fn settings_round_trip_through_toml() {
    let mut s = ShadeSettings::defaults_for(&data(1));
    s.shaders = vec![ShaderKind::Frequency, ShaderKind::Time];
    s.time.mode = TimeMode::Travel;
    s.objects.get_mut("ball").unwrap().texture = "checker:3x5".parse().unwrap();
    let text = s.to_toml();
    let back: ShadeSettings = toml::from_str(&text).unwrap();
    assert_eq!(back, s);
}

#[test]
fn overlay_replaces_given_fields_and_names_unknown_ones() {
    let s = ShadeSettings::defaults_for(&data(0));
    let text = "exposure = 2\nshaders = [\"frequency\"]\n[objects.ball]\ntemperature = 3000\ntexture = { kind = \"gradient\" }\n";
    let o = s.overlay_toml(text, "s.toml").unwrap();
    assert_eq!(o.exposure, 2.0);
    assert_eq!(o.objects["ball"].temperature, 3000.0);
    assert_eq!(o.objects["ball"].texture, TextureChoice::Gradient);
    assert_eq!(o.objects["moon"], s.objects["moon"]);

    let e = s
        .overlay_toml(
            "exposure = 1.0\n[objects.ball]\ntempreature = 3\n",
            "s.toml",
        )
        .unwrap_err();
    let m = e.to_string();
    assert!(
        m.starts_with("s.toml:3: objects.ball.tempreature: unknown field"),
        "{m}"
    );
    let e = s
        .overlay_toml("[objects.sun]\ntemperature = 3\n", "s.toml")
        .unwrap_err();
    assert!(e.to_string().contains("unknown object 'sun'"), "{e}");
    let e = s
        .overlay_toml("shaders = [\"sepia\"]\n", "s.toml")
        .unwrap_err();
    assert!(matches!(e, ShadeError::Settings { .. }), "{e}");
    assert!(e.to_string().contains("sepia"), "{e}");
}

#[test]
fn a_saved_keyframe_pastes_into_a_script() {
    let d = data(1);
    let mut s = ShadeSettings::defaults_for(&d);
    s.objects.get_mut("moon").unwrap().temperature = 7777.0;
    s.exposure = 0.5;
    let script = format!("data = \"x.exr\"\nframes = 10\n\n{}", keyframe_toml(4, &s));
    let parsed = Script::parse(&script, Path::new("seq.toml")).unwrap();
    assert_eq!(parsed.keyframes.len(), 1);
    assert_eq!(parsed.keyframes[0].frame, 4);
    let timeline = parsed.timeline(&ShadeSettings::defaults_for(&d)).unwrap();
    assert_eq!(timeline.settings_at(0), s);
    assert_eq!(timeline.settings_at(9), s);
}

/// Fuzzing found messages of two lines: a settings or script file that quotes a line break
/// (an unknown object `"a\nb"`, an unknown variant `"line\nbreak"`, an image path) put it
/// into the message. Every message is one line, the control characters escaped.
#[test]
fn regression_fuzz_settings_and_script_errors_are_one_line() {
    let base = ShadeSettings::defaults_for(&data(1));
    let cases = [
        "[objects.\"a\\nb\"]\ntemperature = 3000.0\n",
        "brightness = \"line\\nbreak\"\n",
        "[objects.ball]\ntexture = { kind = \"image\", path = \"no\\nsuch.png\" }\n",
    ];
    for text in cases {
        let e = match base.overlay_toml(text, "odd\nname.toml") {
            Err(e) => e,
            Ok(s) => shade::Shading::new(&data(1), &s).unwrap_err(),
        };
        let shown = e.to_string();
        assert!(!shown.contains('\n'), "{text:?}: {shown:?}");
        assert!(shown.contains("\\n"), "{text:?}: {shown:?}");
    }
    let e = Script::parse(
        "data = \"d.exr\"\nframes = 2\ninterpolation = \"line\\nbreak\"\n",
        Path::new("seq.toml"),
    )
    .unwrap_err();
    assert!(!e.to_string().contains('\n'), "{e}");
    assert!(e.to_string().contains("line\\nbreak"), "{e}");
}

/// Fuzzing found settings errors at line 1 with no field: a value of the wrong type or an
/// unknown variant was reported only after the merge, where no path was kept. Now the
/// message names the field and its line, in settings files and in scripts.
#[test]
fn regression_fuzz_settings_errors_name_the_field_and_line() {
    let base = ShadeSettings::defaults_for(&data(1));
    for (text, line, field) in [
        (
            "exposure = 1.0\n\nbrightness = \"bright\"\n",
            3,
            "brightness",
        ),
        ("[time]\nt0 = -1.0\nlegend = 1\n", 3, "time.legend"),
        (
            "[objects.ball]\nrotation_deg = 3.0\ntexture = { kind = \"checker\" }\n",
            3,
            "objects.ball.texture",
        ),
        (
            "[light]\nsources = [{ on = true, intensity = \"x\", color = [1.0, 1.0, 1.0] }]\n",
            2,
            "light.sources[0].intensity",
        ),
    ] {
        match base.overlay_toml(text, "look.toml") {
            Err(ShadeError::Settings {
                line: l, field: f, ..
            }) => {
                assert_eq!((l, f.as_str()), (line, field), "{text}");
            }
            other => panic!("{text}: {other:?}"),
        }
    }
    let script = Script::parse(
        "data = \"d.exr\"\nframes = 4\n[[keyframe]]\nframe = 1\n[keyframe.settings]\nbrightness = \"bright\"\n",
        Path::new("seq.toml"),
    )
    .unwrap();
    match script.timeline(&base) {
        Err(ShadeError::Script { line, field, .. }) => {
            assert_eq!(
                (line, field.as_str()),
                (6, "keyframe[0].settings.brightness")
            );
        }
        other => panic!("{other:?}"),
    }
}
