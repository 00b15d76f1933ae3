//! The routes that feed the page's GPU shaders and look around a full sphere, without a
//! browser: requests go straight into the router, on data files built in memory whose every
//! pixel is known. The arrays on the wire must hold the data file's values exactly, the
//! tables the `shade` crate's, and the looked-at pictures `look` + `shade`'s.

use crate::gpu_common::*;
use axum::http::StatusCode;
use datafile::{DataFile, PixelRecord, RayStatus};
use look::{look, LookView};
use scene::Camera;
use shade::{ShadeSettings, ShaderKind, Shading};
use spacetime::LocalVelocity;
use viewer::wire::{read_header, SampleType, HEADER_LEN};

/// The samples of a wire array as u32 (integers) or f32 bits, after checking the header.
fn samples(body: &[u8], kind: SampleType, components: u8, size: (usize, usize)) -> Vec<u32> {
    let (w, h, k, c) = read_header(body).expect("a wire array");
    assert_eq!((w, h, k, c), (size.0, size.1, kind, components));
    let data = &body[HEADER_LEN..];
    assert_eq!(data.len(), w * h * usize::from(c) * kind.size());
    data.chunks_exact(kind.size())
        .map(|b| match kind {
            SampleType::U8 => u32::from(b[0]),
            SampleType::U16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
            _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        })
        .collect()
}

#[tokio::test]
async fn channels_hold_the_data_files_values_exactly() {
    let data = || {
        let mut d = data();
        d.records[3] = PixelRecord {
            object: 7, // no such object
            status: RayStatus::Hit,
            ..PixelRecord::MISS
        };
        d.records[4] = PixelRecord::miss(RayStatus::WorkLimit);
        for (i, r) in d.records.iter_mut().enumerate() {
            r.pol = [0.25 * i as f32, -(i as f32), 0.5];
        }
        d
    };
    let d = data();
    for (name, get_value) in [
        ("u", (|r: &PixelRecord| r.u) as fn(&PixelRecord) -> f32),
        ("v", |r| r.v),
        ("g", |r| r.g),
        ("t_emit", |r| r.t_emit),
    ] {
        let (status, body) = send(data(), get(&format!("/api/gpu/channel/{name}"))).await;
        assert_eq!(status, StatusCode::OK, "{name}");
        let got = samples(&body, SampleType::F32, 1, (W, H));
        let want: Vec<u32> = d.records.iter().map(|r| get_value(r).to_bits()).collect();
        assert_eq!(got, want, "{name}");
    }
    // pol and dir: three components a sample, as the polarization layer reads them.
    for (name, get_value) in [
        (
            "pol",
            (|r: &PixelRecord| r.pol) as fn(&PixelRecord) -> [f32; 3],
        ),
        ("dir", |r| r.dir),
    ] {
        let (status, body) = send(data(), get(&format!("/api/gpu/channel/{name}"))).await;
        assert_eq!(status, StatusCode::OK, "{name}");
        let got = samples(&body, SampleType::F32, 3, (W, H));
        let want: Vec<u32> = (d.records.iter())
            .flat_map(|r| get_value(r).map(f32::to_bits))
            .collect();
        assert_eq!(got, want, "{name}");
    }
    let (_, body) = send(data(), get("/api/gpu/channel/light_0")).await;
    let want: Vec<u32> = d.lights[0].iter().map(|x| x.to_bits()).collect();
    assert_eq!(samples(&body, SampleType::F32, 1, (W, H)), want);

    // cos_i as the Lambert factor reads it: clamped to [0, 1], NaN as 0, in 1/65535 steps.
    let (_, body) = send(data(), get("/api/gpu/channel/cos_i")).await;
    let got = samples(&body, SampleType::U16, 1, (W, H));
    for (i, r) in d.records.iter().enumerate() {
        let c = if r.cos_i.is_nan() {
            0.0
        } else {
            r.cos_i.clamp(0.0, 1.0)
        };
        assert!((got[i] as f32 / 65535.0 - c).abs() <= 0.5 / 65535.0, "{i}");
    }

    // What each pixel shows: background 0, failed 1, step budget (or work limit) 2, not traced
    // 3, object k at 4 + k; an object the file does not name shows as failed, as the shade
    // crate colours it.
    let (_, body) = send(data(), get("/api/gpu/channel/id")).await;
    let ids = samples(&body, SampleType::U8, 1, (W, H));
    assert_eq!(&ids[..6], &[1, 2, 3, 1, 2, 0]);
    assert_eq!(ids[3 * W + 11], 4);
    assert_eq!(ids[4 * W + 8], 5);
    assert_eq!(ids.iter().filter(|&&id| id >= 4).count(), 8);
}

#[tokio::test]
async fn unknown_channels_are_404_and_name_the_files_channels() {
    for name in ["w", "light_1", "light_01", "light_", "object"] {
        let (status, body) = send(data(), get(&format!("/api/gpu/channel/{name}"))).await;
        assert_eq!(status, StatusCode::NOT_FOUND, "{name}");
        let message = json(&body)["error"].as_str().unwrap().to_string();
        assert!(
            message.contains(name) && message.contains("light_0"),
            "{message}"
        );
    }
}

#[tokio::test]
async fn scene_textures_and_images_are_the_shade_crates() {
    let (status, body) = send(data(), get("/api/gpu/textures")).await;
    assert_eq!(status, StatusCode::OK);
    let objects = &json(&body)["objects"];
    assert_eq!(objects[0]["kind"], "uniform");
    let colour: Vec<f64> = (0..3)
        .map(|i| objects[0]["color"][i].as_f64().unwrap())
        .collect();
    assert_eq!(colour, [0.2f32, 0.4, 0.6].map(f64::from));
    assert_eq!(
        objects[1],
        serde_json::json!({"kind": "image", "image": "scene-1", "width": 720, "height": 360})
    );
    let earth = shade::ImageTexture::earth().unwrap();
    let want: Vec<u32> = earth
        .srgb8()
        .iter()
        .flat_map(|p| p.map(u32::from))
        .collect();
    for name in ["scene-1", "earth"] {
        let (status, body) = send(data(), get(&format!("/api/gpu/image/{name}"))).await;
        assert_eq!(status, StatusCode::OK);
        assert_eq!(
            samples(&body, SampleType::U8, 3, (720, 360)),
            want,
            "{name}"
        );
    }
    for name in ["scene-0", "scene-2", "moon"] {
        let (status, _) = send(data(), get(&format!("/api/gpu/image/{name}"))).await;
        assert_eq!(status, StatusCode::NOT_FOUND, "{name}");
    }
}

#[tokio::test]
async fn black_body_tables_are_the_shade_crates() {
    let (_, body) = send(data(), get("/api/gpu/blackbody")).await;
    let bb = json(&body);
    let table = shade::blackbody::table();
    let (ln_t_min, step) = table.grid();
    assert_eq!(bb["ln_t_min"].as_f64().unwrap(), ln_t_min);
    assert_eq!(bb["step"].as_f64().unwrap(), step);
    // JSON carries f64 exactly (shortest round-trip digits, which the page's JSON.parse reads
    // back exactly); serde_json's own parser may miss the last bit.
    let same = |a: f64, b: f64| (a - b).abs() <= 2.0 * f64::EPSILON * b.abs();
    for (i, (unit, ln_y)) in table.nodes().enumerate() {
        assert!(same(bb["ln_y"][i].as_f64().unwrap(), ln_y));
        for (k, c) in unit.iter().enumerate() {
            assert!(same(bb["unit"][i][k].as_f64().unwrap(), *c));
        }
    }
    // Independently of the tables: node colours interpolated at 5800 K are the direct
    // integral's colour of a 5800 K black body.
    let s = (5800f64.ln() - ln_t_min) / step;
    let (i, f) = (s.floor() as usize, s - s.floor());
    let direct = shade::blackbody::unit_colour(5800.0);
    for k in 0..3 {
        let a = bb["unit"][i][k].as_f64().unwrap();
        let b = bb["unit"][i + 1][k].as_f64().unwrap();
        assert!((a + f * (b - a) - direct[k]).abs() < 1e-4);
    }

    // The g·T table: entry of bin(T) is the one the CPU shader reads at T.
    let (_, body) = send(data(), get("/api/gpu/blackbody/gt")).await;
    let bins = bb["gt_bins"].as_u64().unwrap() as usize;
    let first = bb["gt_first_bin"].as_u64().unwrap() as u32;
    let shift = bb["gt_shift"].as_u64().unwrap() as u32;
    let values = samples(&body, SampleType::F32, 4, (bins, 2));
    let f = |i: usize| f32::from_bits(values[i]);
    for t in [1000.0f64, 2500.5, 5800.0, 31_000.0, 100_000.0] {
        let i = (((t as f32).to_bits() >> shift) - first) as usize;
        let e = shade::gt_table::gt_table().get(t).unwrap();
        assert_eq!([f(i * 4), f(i * 4 + 1), f(i * 4 + 2)], e.unit, "{t}");
        assert_eq!(f(i * 4 + 3), e.luminance as f32);
        let n = (bins + i) * 4;
        assert_eq!([f(n), f(n + 1), f(n + 2)], e.normalized, "{t}");
    }
}

#[tokio::test]
async fn view_says_whether_the_page_can_look_around() {
    let (_, body) = send(data(), get("/api/view")).await;
    let view = json(&body);
    assert_eq!(view["sphere"], true);
    assert_eq!(view["view"]["camera"]["kind"], "sphere");
    // The ball shows at 90° to the right (−y), the globe ahead (+x).
    let dir = |k: usize| [0, 1, 2].map(|i| view["object_directions"][k][i].as_f64().unwrap());
    assert!(dir(0)[1] < -0.99, "{:?}", dir(0));
    assert!(dir(1)[0] > 0.99, "{:?}", dir(1));

    let (view, why) = refused_view(flat()).await;
    assert!(why.contains("full-sphere"), "{why}");
    assert_eq!(view["view"]["camera"]["fov_deg"], 60.0);

    // An anti-aliased sphere (its 16×8 records as 2×2 rays per pixel) is refused as `godel
    // look` refuses it, saying why; the page shows it as a picture.
    let mut sampled = data();
    sampled.header.supersample = 2;
    let (_, why) = refused_view(sampled).await;
    assert!(why.contains("2×2 rays per pixel"), "{why}");
}

/// The answer of `/api/view` for `data`, which must say that the page cannot look around,
/// and the reason it gives.
async fn refused_view(data: DataFile) -> (serde_json::Value, String) {
    let (_, body) = send(data, get("/api/view")).await;
    let view = json(&body);
    assert_eq!(view["sphere"], false);
    let why = view["sphere_error"].as_str().unwrap().to_string();
    (view, why)
}

fn look_body(speed: f64) -> (String, ShadeSettings, LookView) {
    let mut settings = ShadeSettings::defaults_for(&data());
    settings.shaders = vec![ShaderKind::Frequency, ShaderKind::Texture];
    let view = LookView::new(
        Camera::Pinhole {
            fov_deg: 100.0,
            width: 12,
            height: 7,
        },
        [0.6, 0.8, 0.0],
        [0.0, 0.0, 1.0],
        LocalVelocity::new(speed, [0.0, 1.0, 0.0]).unwrap(),
    )
    .unwrap();
    let body = serde_json::json!({
        "settings": settings,
        "view": {"camera": {"kind": "pinhole", "fov_deg": 100.0, "width": 12, "height": 7},
                 "forward": view.forward, "up": view.up,
                 "velocity": {"speed": speed, "direction": [0.0, 1.0, 0.0]}},
    });
    (body.to_string(), settings, view)
}

#[tokio::test]
async fn looked_pictures_are_look_then_shade() {
    let (body, settings, view) = look_body(0.7);
    let looked = look(&data(), &view).unwrap();
    let want = Shading::new(&looked, &settings).unwrap().image(&looked);
    let (status, rgba) = send(data(), post("/api/look/image", body.clone())).await;
    assert_eq!(status, StatusCode::OK);
    let rgb: Vec<u8> = rgba
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    assert_eq!(rgb, want.as_raw().to_vec());
    let (status, png) = send(data(), post("/api/look/png", body)).await;
    assert_eq!(status, StatusCode::OK);
    assert!(image::load_from_memory(&png).unwrap().to_rgb8() == want);
    // The boost matters: at rest the picture differs.
    let (body, _, _) = look_body(0.0);
    let (_, rest) = send(data(), post("/api/look/image", body)).await;
    assert_ne!(rest, rgba);
}

#[tokio::test]
async fn bad_views_get_400_naming_the_field() {
    let (body, _, _) = look_body(0.5);
    let mut value: serde_json::Value = serde_json::from_str(&body).unwrap();
    for (change, needle) in [
        (
            (|v: &mut serde_json::Value| v["view"]["velocity"]["speed"] = 1.2.into())
                as fn(&mut serde_json::Value),
            "velocity",
        ),
        (
            |v| {
                v["view"]["camera"] =
                    serde_json::json!({"kind": "fisheye", "fov_deg": 180, "width": 8, "height": 9})
            },
            "square",
        ),
        (|v| v["view"]["camera"]["fov_deg"] = 180.0.into(), "fov_deg"),
        (
            |v| v["view"]["up"] = serde_json::json!([0.6, 0.8, 0.0]),
            "orthogonal",
        ),
        (
            |v| v["view"]["zoom"] = 2.into(),
            "look.view.zoom: unknown field `zoom`",
        ),
        (
            |v| v["settings"]["exposure"] = "x".into(),
            "look.settings.exposure: invalid type",
        ),
        (|v| v["settings"]["exposure"] = (-1.0).into(), "exposure"),
    ] {
        let mut bad = value.clone();
        change(&mut bad);
        let (status, answer) = send(data(), post("/api/look/image", bad.to_string())).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{needle}");
        let message = json(&answer)["error"].as_str().unwrap().to_string();
        assert!(message.contains(needle), "{needle}: {message}");
    }
    // A file that is not a full sphere cannot be looked around.
    value["view"]["velocity"]["speed"] = 0.0.into();
    let (status, answer) = send(flat(), post("/api/look/png", value.to_string())).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(json(&answer)["error"]
        .as_str()
        .unwrap()
        .contains("full-sphere"));
}
