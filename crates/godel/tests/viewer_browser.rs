//! The live viewer in a real browser: renders a small scene with `godel render`, serves its
//! data file with `godel view --port 0`, and drives Debian's chromium through playwright-core
//! (tests/browser/viewer.mjs): move the temperature slider, hover a hit pixel, press both save
//! buttons, send bad settings, take a screenshot. This test checks what the browser saw
//! against the data file and the `shade` crate. Chromium and the npm packages are installed
//! by `bash scripts/test.sh`; without them this test fails and says so.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use datafile::record::RayStatus;
use datafile::DataFile;
use shade::{ShadeSettings, ShaderKind, Shading};

/// A 96×48 pinhole view of a checkered ball at rest inside the horizon.
const SCENE: &str = r#"
name = "viewer-test"
[spacetime]
metric = "godel"
a = 1.0
[observer]
time = 0.0
position = { r = 0.0, phi = 0.0, z = 0.0 }
forward = [1, 0, 0]
up = [0, 0, 1]
[camera]
kind = "pinhole"
fov_deg = 60.0
width = 96
height = 48
[trace]
method = "numeric"
max_past = 10.0
[[object]]
name = "ball"
radius = 0.2
texture = { kind = "checker", rows = 8, cols = 16 }
temperature = 5800.0
motion = { kind = "rest", position = { r = 1.0, phi = 0.0, z = 0.0 } }
"#;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn chromium() -> PathBuf {
    std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"))
}

/// Fails (never skips) when the browser or the npm packages are missing.
fn require_browser_tools() {
    let chromium = chromium();
    assert!(
        chromium.exists(),
        "{} is missing: run `bash scripts/test.sh`, which installs Debian's chromium",
        chromium.display()
    );
    let playwright = repo_root().join("tests/browser/node_modules/playwright-core");
    assert!(
        playwright.exists(),
        "{} is missing: run `bash scripts/test.sh`, which runs `npm ci` in tests/browser",
        playwright.display()
    );
}

/// The `godel view` server, killed when dropped.
struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts `godel view DATA --port 0`; returns it and the URL it printed.
fn start_viewer(data: &Path) -> (Server, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_godel"))
        .args(["view", data.to_str().unwrap(), "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .expect("start godel view");
    let stdout = child.stdout.take().unwrap();
    let server = Server(child);
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = send.send(line);
    });
    // A deadline against hanging forever, not a speed check.
    let line = receive
        .recv_timeout(Duration::from_secs(120))
        .expect("godel view printed no URL");
    let url = line
        .trim()
        .strip_prefix("godel view: serving ")
        .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
        .to_string();
    assert!(
        url.starts_with("http://127.0.0.1:") && url.ends_with('/'),
        "{url}"
    );
    (server, url)
}

fn number(text: &serde_json::Value) -> f64 {
    text.as_str()
        .unwrap_or_else(|| panic!("{text} is not text"))
        .parse()
        .unwrap_or_else(|_| panic!("{text} is not a number"))
}

#[test]
fn browser_moves_slider_reads_record_saves_and_shows_errors() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("viewer-test.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let rendered = Command::new(env!("CARGO_BIN_EXE_godel"))
        .args(["render", scene.to_str().unwrap(), "-q", "-o"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(rendered.status.success(), "{rendered:?}");
    let exr = dir.path().join("viewer-test.exr");
    let data = DataFile::read(&exr).unwrap();

    // The hit pixel nearest the centre of the ball's image.
    let hits: Vec<(usize, usize)> = (0..data.height)
        .flat_map(|row| (0..data.width).map(move |col| (col, row)))
        .filter(|&(col, row)| data.record(col, row).status == RayStatus::Hit)
        .collect();
    assert!(hits.len() > 20, "the test scene shows the ball");
    let mean = |f: fn(&(usize, usize)) -> usize| {
        hits.iter().map(f).sum::<usize>() as f64 / hits.len() as f64
    };
    let (cx, cy) = (mean(|p| p.0), mean(|p| p.1));
    let &(col, row) = hits
        .iter()
        .min_by(|a, b| {
            let d = |p: &(usize, usize)| (p.0 as f64 - cx).powi(2) + (p.1 as f64 - cy).powi(2);
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let expected = *data.record(col, row);

    let (server, url) = start_viewer(&exr);
    let out = dir.path().join("browser");
    std::fs::create_dir(&out).unwrap();
    let browser = Command::new("node")
        .current_dir(repo_root().join("tests/browser"))
        .env("CHROMIUM", chromium())
        .arg("viewer.mjs")
        .arg(&url)
        .arg(&out)
        .args([col.to_string(), row.to_string()])
        .output()
        .expect("run node (installed with chromium by scripts/test.sh)");
    drop(server);
    assert!(
        browser.status.success(),
        "browser script failed:\n{}\n{}",
        String::from_utf8_lossy(&browser.stdout),
        String::from_utf8_lossy(&browser.stderr)
    );
    let seen: serde_json::Value = serde_json::from_slice(&browser.stdout).expect("one JSON object");
    // Figures for BENCHMARKS.md, not checked: timing depends on the machine's load.
    eprintln!("round trips (ms): {}", seen["round_trips_ms"]);
    eprintln!("server timings (ms): {}", seen["server_timings_ms"]);

    assert_eq!(seen["title"], "godel view");
    assert_eq!(seen["canvas"], serde_json::json!([data.width, data.height]));

    // The slider moved down, and the picture followed.
    let t_before = seen["temperature"][0].as_f64().unwrap();
    let t_after = seen["temperature"][1].as_f64().unwrap();
    assert_eq!(
        t_before, 5800.0,
        "the slider starts at the scene's temperature"
    );
    assert!(
        t_after < 4000.0,
        "the drag moved the slider down: {t_after}"
    );
    assert!(seen["frames_for_drag"].as_u64().unwrap() >= 1);
    let changed = seen["pixels_changed"].as_u64().unwrap() as usize;
    assert!(
        changed * 10 >= hits.len() * 9 && changed < data.width * data.height,
        "{changed} pixels changed; the ball has {} pixels",
        hits.len()
    );

    // The record shown on hover is the data file's.
    let shown = &seen["record_shown"];
    // Shown larger than its size, the picture puts the mouse on exactly the pixel aimed at.
    assert_eq!(shown["pixel"], format!("{col}, {row}"));
    assert_eq!(shown["object"], "ball");
    assert_eq!(shown["status"], "hit");
    for (field, value) in [
        ("u", expected.u),
        ("v", expected.v),
        ("g", expected.g),
        ("t_emit", expected.t_emit),
        ("travel_time", -expected.t_emit),
    ] {
        let got = number(&shown[field]);
        assert!(
            (got - f64::from(value)).abs() <= 6e-5,
            "{field}: page shows {got}, file has {value}"
        );
    }
    assert!(expected.t_emit < 0.0);
    // The viewing direction shown is the camera's for that pixel (one decimal on the page).
    let camera = scene::Scene::from_str(&data.header.scene_text, "embedded")
        .unwrap()
        .camera;
    let (az, el) = scene::azimuth_elevation(
        camera
            .pixel_direction(col as u32, row as u32)
            .expect("a hit pixel is traced"),
    );
    assert_eq!(
        shown["direction"],
        format!("az {az:.1}°, el {el:.1}°"),
        "the page's direction for pixel {col}, {row}"
    );

    // The page's settings are the file's defaults with the frequency layer alone at the
    // slider's temperature.
    let mut want_settings = ShadeSettings::defaults_for(&data);
    want_settings.shaders = vec![ShaderKind::Frequency];
    want_settings.objects.get_mut("ball").unwrap().temperature = t_after;
    let settings: ShadeSettings = serde_json::from_value(seen["settings"].clone()).unwrap();
    assert_eq!(settings, want_settings);

    // "Save PNG" downloads the server's shading of those settings, as the shade crate
    // (and so `godel shade`) makes it.
    assert_eq!(seen["png_name"], "viewer-test.png");
    let saved = image::open(out.join("saved.png")).unwrap().to_rgb8();
    let want = Shading::new(&data, &want_settings).unwrap().image(&data);
    assert!(saved == want, "the saved PNG is not the shaded view");

    // "Save keyframe" downloads a sequence-script keyframe holding those settings.
    assert_eq!(seen["keyframe_name"], "viewer-test.keyframe.toml");
    let keyframe: toml::Value =
        toml::from_str(&std::fs::read_to_string(out.join("keyframe.toml")).unwrap()).unwrap();
    let saved_settings: ShadeSettings = keyframe["keyframe"][0]["settings"]
        .clone()
        .try_into()
        .unwrap();
    assert_eq!(saved_settings, want_settings);

    // Bad settings from the page: the server's 400 message is shown on the page.
    assert_eq!(seen["error_shown"], true);
    let error = seen["error_text"].as_str().unwrap();
    assert!(
        error.contains("shader") && error.contains("sepia"),
        "{error}"
    );
    for message in seen["console_errors"].as_array().unwrap() {
        assert!(message.as_str().unwrap().contains("400"), "{message}");
    }

    let screenshot = image::open(out.join("screenshot.png")).unwrap();
    assert!(screenshot.width() >= 800 && screenshot.height() >= 400);
}
