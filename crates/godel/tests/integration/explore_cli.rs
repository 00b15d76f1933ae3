//! `godel explore`: the full frame served for an event holds the records `godel render` writes
//! for the scene with its observer at that event (the channels the page shades, bit for bit),
//! at the scene's width × height; a bad event gets 400 naming the field.

use std::io::{Read, Write};
use std::path::Path;

use std::time::Duration;

use crate::common::{self, port_of, start_server, start_server_with, Server};

/// scenes/static-sphere.toml at 48×8 pixels of 2×2 rays, its observer at `observer` (the
/// lines of the `[observer]` table for time and position).
fn scene_text(observer: &str) -> String {
    std::fs::read_to_string(testkit::scenes_dir().join("static-sphere.toml"))
        .unwrap()
        .replace("width = 720", "width = 48")
        .replace("height = 120", "height = 8\nsamples = 4")
        .replace(
            "time = 0.0\nposition = { r = 0.0, phi = 0.0, z = 0.0 }",
            observer,
        )
}

/// Writes [`scene_text`] with the observer at the origin at t = 0 into `dir` as s.toml.
fn origin_scene(dir: &Path) -> std::path::PathBuf {
    let scene = dir.join("s.toml");
    let observer = "time = 0.0\nposition = { x = 0.0, y = 0.0, z = 0.0 }";
    std::fs::write(&scene, scene_text(observer)).unwrap();
    scene
}

/// One HTTP/1.1 request over a fresh connection; returns the status and the body's bytes.
fn http(port: u16, method: &str, path: &str, body: &str) -> (u16, Vec<u8>) {
    let mut stream = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    // A deadline against hanging forever, not a speed check.
    stream
        .set_read_timeout(Some(Duration::from_secs(60)))
        .unwrap();
    let host = format!("127.0.0.1:{port}");
    let request = format!(
        "{method} {path} HTTP/1.1\r\nHost: {host}\r\nOrigin: http://{host}\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    );
    stream.write_all(request.as_bytes()).unwrap();
    let mut answer = Vec::new();
    stream.read_to_end(&mut answer).unwrap();
    let split = answer
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header");
    let head = String::from_utf8_lossy(&answer[..split]).to_string();
    let status = head.split(' ').nth(1).unwrap().parse().unwrap();
    (status, answer[split + 4..].to_vec())
}

fn json(bytes: &[u8]) -> serde_json::Value {
    serde_json::from_slice(bytes).unwrap()
}

/// The frame `/api/explore/frame` reports once it is the full one of `generation` (any
/// generation if `None`), or the last one seen after a minute (a deadline, not a speed check).
fn full_frame(port: u16, generation: Option<u64>) -> serde_json::Value {
    let mut frame = serde_json::Value::Null;
    for _ in 0..6000 {
        frame = json(&http(port, "GET", "/api/explore/frame", "").1)["frame"].clone();
        let of = generation.is_none_or(|g| frame["generation"] == g);
        if of && frame["level"] == "full" {
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    frame
}

/// Starts `godel explore scene`; returns the server and its port.
fn explore(scene: &Path) -> (Server, u16) {
    let (server, url) = start_server("explore", scene, scene.parent().unwrap());
    (server, port_of(&url))
}

/// The f32 samples of a wire array (16-byte header).
fn floats(bytes: &[u8]) -> Vec<u32> {
    bytes[viewer::wire::HEADER_LEN..]
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// The channels explore serves for the full frame of `generation` are those of `rendered`'s
/// records, bit for bit (what the page shades).
fn assert_channels_are(port: u16, generation: u64, rendered: &datafile::DataFile) {
    let channel = |name: &str| {
        let path = format!("/api/explore/channel/{name}?generation={generation}&level=full");
        let (status, bytes) = http(port, "GET", &path, "");
        assert_eq!(status, 200, "{name}: {}", String::from_utf8_lossy(&bytes));
        let header = viewer::wire::read_header(&bytes).unwrap();
        assert_eq!(
            (header.0, header.1),
            (rendered.width, rendered.height),
            "{name}"
        );
        bytes
    };
    type Field = fn(&datafile::PixelRecord) -> f32;
    let fields: [(&str, Field); 4] = [
        ("u", |r| r.u),
        ("v", |r| r.v),
        ("g", |r| r.g),
        ("t_emit", |r| r.t_emit),
    ];
    for (name, get) in fields {
        let served = floats(&channel(name));
        let expected: Vec<u32> = rendered.records.iter().map(|r| get(r).to_bits()).collect();
        assert_eq!(served, expected, "channel {name}");
    }
    let ids = channel("id");
    let objects = rendered.header.object_names.len();
    let expected: Vec<u8> = rendered
        .records
        .iter()
        .map(|r| viewer::gpu::id_code(r, objects) as u8)
        .collect();
    assert_eq!(
        &ids[viewer::wire::HEADER_LEN..],
        &expected[..],
        "channel id"
    );
}

#[test]
fn the_frame_of_a_flown_view_is_godel_render_of_that_view() {
    let dir = tempfile::tempdir().unwrap();
    let scene = origin_scene(dir.path());
    let (_server, port) = explore(&scene);
    // A flown view: moved, moving at 0.5 c, turned, a pinhole of 24×8 pixels of 2×2 rays.
    let view = serde_json::json!({
        "time": 0.75, "position": {"x": 0.25, "y": 0.125, "z": 0.0},
        "velocity": {"speed": 0.5, "direction": [0.0, 1.0, 0.0]},
        "forward": [1.0, 0.25, 0.0], "up": [0.0, 0.0, 1.0],
        "camera": {"kind": "pinhole", "fov_deg": 75.0, "width": 24, "height": 8, "samples": 4},
    });
    let (status, body) = http(port, "POST", "/api/explore/view-frame", &view.to_string());
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    let generation = json(&body)["generation"].as_u64().unwrap();
    let frame = full_frame(port, Some(generation));
    assert_eq!(
        (
            frame["width"].as_u64(),
            frame["height"].as_u64(),
            frame["supersample"].as_u64()
        ),
        (Some(24), Some(8), Some(2)),
        "{frame}"
    );
    assert_eq!(frame["event"]["t"], 0.75, "{frame}");
    let answer = json(&http(port, "GET", "/api/explore/frame", "").1);
    assert!(
        answer["cpu_rays_per_ms"].as_f64().is_some_and(|r| r > 0.0),
        "{answer}"
    );

    // godel render of the scene with the view's observer and camera.
    let moved = dir.path().join("viewed.toml");
    let text = scene_text(
        "time = 0.75\nposition = { x = 0.25, y = 0.125, z = 0.0 }\n\
         velocity = { speed = 0.5, direction = [0.0, 1.0, 0.0] }",
    );
    let mut table: toml::Table = text.parse().unwrap();
    let observer = table["observer"].as_table_mut().unwrap();
    observer.insert(
        "forward".into(),
        toml::Value::try_from([1.0, 0.25, 0.0]).unwrap(),
    );
    observer.insert("up".into(), toml::Value::try_from([0.0, 0.0, 1.0]).unwrap());
    let camera: toml::Table =
        "kind = \"pinhole\"\nfov_deg = 75.0\nwidth = 24\nheight = 8\nsamples = 4"
            .parse()
            .unwrap();
    table.insert("camera".into(), camera.into());
    std::fs::write(&moved, toml::to_string(&table).unwrap()).unwrap();
    let out = dir.path().join("out");
    let o = common::render(&moved, &out, &["-q", "--method", "exact"]);
    assert!(o.status.success(), "{o:?}");
    let rendered = datafile::DataFile::read(&out.join("static-sphere.exr")).unwrap();
    assert_eq!((rendered.width, rendered.height), (48, 16));
    let hits = rendered.records.iter().filter(|r| r.has_emission()).count();
    assert!(hits > 0, "the flown view sees the ball");
    assert_channels_are(port, generation, &rendered);

    // More rays than a frame of the scene's camera (48×8 of 2×2) is refused, naming the field.
    let mut big = view.clone();
    big["camera"]["width"] = 100.into();
    let (status, body) = http(port, "POST", "/api/explore/view-frame", &big.to_string());
    assert_eq!(status, 400);
    let why = json(&body)["error"].as_str().unwrap().to_string();
    assert!(why.starts_with("view.camera: 200×16 samples"), "{why}");
}

#[test]
fn the_full_frame_for_an_event_is_godel_render_of_that_observer() {
    let dir = tempfile::tempdir().unwrap();
    let scene = origin_scene(dir.path());
    let (_server, port) = explore(&scene);

    // Bad events change nothing and name the field.
    let (status, body) = http(
        port,
        "POST",
        "/api/explore/event",
        r#"{"t":0,"x":0,"y":5e6,"z":0}"#,
    );
    assert_eq!(status, 400);
    assert!(json(&body)["error"].as_str().unwrap().contains("event.y"));

    let event_json = r#"{"t": 1.5, "x": 0.25, "y": -0.125, "z": 0.0625}"#;
    let (status, body) = http(port, "POST", "/api/explore/event", event_json);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    let generation = json(&body)["generation"].as_u64().unwrap();
    // The first request (the scene's own event) and then this one.
    assert_eq!(generation, 2);
    let frame = full_frame(port, Some(generation));
    assert_eq!(frame["level"], "full", "{frame}");
    assert_eq!(
        (frame["width"].as_u64(), frame["height"].as_u64()),
        (Some(48), Some(8))
    );
    assert_eq!(frame["supersample"], 2);

    // godel render of the scene with that observer.
    let moved = dir.path().join("moved.toml");
    let observer = "time = 1.5\nposition = { x = 0.25, y = -0.125, z = 0.0625 }";
    std::fs::write(&moved, scene_text(observer)).unwrap();
    let out = dir.path().join("out");
    // Explore traces with the exact tracer.
    let o = common::render(&moved, &out, &["-q", "--method", "exact"]);
    assert!(o.status.success(), "{o:?}");
    let rendered = datafile::DataFile::read(&out.join("static-sphere.exr")).unwrap();
    assert_eq!((rendered.width, rendered.height), (96, 16));
    let hits = rendered
        .records
        .iter()
        .filter(|r| r.status == datafile::RayStatus::Hit)
        .count();
    assert!(hits > 0, "the moved observer still sees the ball");

    assert_channels_are(port, generation, &rendered);

    // The map's ray of each pixel starts at the observer and ends at the pixel's emission
    // event in the records of `godel render` (the sample nearest the pixel's centre).
    let event = [1.5, 0.25, -0.125, 0.0625];
    let mut hits = 0;
    for row in 0..8 {
        for col in 0..48 {
            let path =
                format!("/api/explore/ray?generation={generation}&level=full&col={col}&row={row}");
            let (status, body) = http(port, "GET", &path, "");
            assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
            let ray = json(&body);
            let point =
                |p: &serde_json::Value| ["t", "x", "y", "z"].map(|k| p[k].as_f64().unwrap());
            let points = ray["points"].as_array().unwrap();
            assert_eq!(point(&points[0]), event, "({col}, {row})");
            let r = rendered.records[rendered.index(2 * col + 1, 2 * row + 1)];
            assert_eq!(
                ray["status"] == "hit",
                r.has_emission(),
                "({col}, {row}): {ray}"
            );
            if r.has_emission() {
                hits += 1;
                let expected = [
                    1.5 + f64::from(r.t_emit),
                    f64::from(r.x),
                    f64::from(r.y),
                    f64::from(r.z),
                ];
                // (to the last bits that serde_json's float parsing may change)
                let emission = point(&ray["emission"]);
                for k in 0..4 {
                    assert!(
                        (emission[k] - expected[k]).abs() < 1e-12,
                        "({col}, {row}): {ray}"
                    );
                }
                let last = point(points.last().unwrap());
                for k in 0..4 {
                    assert!(
                        (last[k] - expected[k]).abs() < 2e-4,
                        "({col}, {row}): {ray}"
                    );
                }
                let travel = ray["travel_time"].as_f64().unwrap();
                assert!((travel + f64::from(r.t_emit)).abs() < 1e-12, "{ray}");
            }
        }
    }
    assert!(hits > 5, "{hits} hits");
    let (status, body) = http(
        port,
        "GET",
        &format!("/api/explore/ray?generation={generation}&level=full&col=48&row=0"),
        "",
    );
    assert_eq!(status, 400, "{}", String::from_utf8_lossy(&body));

    // The map for that event: the ball at rest where the scene puts it, the horizon of an
    // observer off the axis (no circle about it), a bad event refused naming the field.
    let (status, body) = http(
        port,
        "GET",
        "/api/explore/map?t=1.5&x=0.25&y=-0.125&z=0.0625",
        "",
    );
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    let map = json(&body);
    assert_eq!(map["horizon_radius"], 2.0);
    assert_eq!(map["horizon"].as_array().unwrap().len(), 256);
    assert_eq!(map["time_range"], serde_json::json!([-28.5, 1.5]));
    let ball = &map["objects"][0];
    assert_eq!(
        (ball["name"].as_str(), ball["moving"].as_bool()),
        (Some("ball"), Some(false))
    );
    assert_eq!(
        (ball["at"]["x"].as_f64(), ball["at"]["y"].as_f64()),
        (Some(1.0), Some(0.0))
    );
    let (status, body) = http(port, "GET", "/api/explore/map?t=1.5&x=0&y=5e6&z=0", "");
    assert_eq!(status, 400);
    assert!(json(&body)["error"]
        .as_str()
        .unwrap()
        .contains("map.y: 5e6"));

    // The keyframe saved for the event puts a fly-through's frame there: a one-frame
    // sequence with it writes the records of `godel render` of that observer.
    let (status, body) = http(port, "POST", "/api/explore/keyframe?frame=0", event_json);
    let keyframe = String::from_utf8(body).unwrap();
    assert_eq!(status, 200, "{keyframe}");
    assert!(keyframe.contains("[keyframe.observer]"), "{keyframe}");
    let script = dir.path().join("fly.toml");
    std::fs::write(
        &script,
        format!(
            "output = \"seq\"\nframes = 1\nfps = 1.0\n[trace]\nscene = \"s.toml\"\n\
             keep_data = true\n[settings]\nshaders = [\"texture\"]\n{keyframe}"
        ),
    )
    .unwrap();
    let o = common::godel(&["sequence", script.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{o:?}");
    let o = common::render(&moved, &out, &["-q"]);
    assert!(o.status.success(), "{o:?}");
    let direct = datafile::DataFile::read(&out.join("static-sphere.exr")).unwrap();
    let framed = datafile::DataFile::read(&dir.path().join("seq/frame_0000.exr")).unwrap();
    assert_eq!(framed.records, direct.records);
}

#[test]
fn a_bad_scene_is_refused_before_serving() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    std::fs::write(
        &scene,
        scene_text("time = \"soon\"\nposition = { x = 0.0 }"),
    )
    .unwrap();
    let o = common::godel(&["explore", scene.to_str().unwrap(), "--port", "0"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(o.stdout.is_empty(), "nothing served");
    assert!(
        stderr.contains("bad.toml") && stderr.contains("observer.time"),
        "{stderr}"
    );
    let o = common::godel(&["explore", "no-such-scene.toml", "--port", "0"]);
    assert_ne!(o.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no-such-scene.toml"));
    // A kernel source (`--kernel FILE`) that cannot be read: refused naming the flag.
    let good = origin_scene(dir.path());
    let missing = dir.path().join("no-such-kernel.glsl");
    let o = common::godel(&[
        "explore",
        good.to_str().unwrap(),
        "--port",
        "0",
        "--kernel",
        missing.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(o.stdout.is_empty(), "nothing served");
    assert!(
        stderr.contains("--kernel") && stderr.contains("no-such-kernel.glsl"),
        "{stderr}"
    );
}

/// `--sphere W`: the frames are the full sphere W × W/2 around the observer, one ray each,
/// so the page can look around in them; the data file says so (its embedded camera), and
/// a width that is odd or out of range is refused before anything is traced or served.
#[test]
fn explore_sphere_traces_the_full_sphere_the_page_can_look_around_in() {
    let dir = tempfile::tempdir().unwrap();
    let scene = origin_scene(dir.path());
    let (server, url) = start_server_with("explore", &scene, dir.path(), &["--sphere", "32"]);
    let port = port_of(&url);
    let (status, body) = http(port, "GET", "/api/view", "");
    assert_eq!(status, 200);
    let view = json(&body);
    assert_eq!(view["sphere"], true, "{view}");
    let frame = full_frame(port, None);
    assert_eq!(
        (
            frame["width"].as_u64(),
            frame["height"].as_u64(),
            frame["supersample"].as_u64()
        ),
        (Some(32), Some(16), Some(1)),
        "{frame}"
    );
    drop(server);
    for bad in ["31", "4", "10000"] {
        let o = common::godel(&[
            "explore",
            scene.to_str().unwrap(),
            "--port",
            "0",
            "--sphere",
            bad,
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bad}: {stderr}");
        assert!(o.stdout.is_empty(), "nothing served");
        assert!(stderr.contains(&format!("--sphere {bad}")), "{stderr}");
    }
}

/// The RGB pixels and size of a PNG.
fn png_pixels(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let image = image::load_from_memory(bytes)
        .unwrap_or_else(|e| panic!("not a PNG ({e}): {}", String::from_utf8_lossy(bytes)))
        .to_rgb8();
    (image.width(), image.height(), image.into_raw())
}

/// Moves the observer of the server on `port` to t = 1.5, (0.25, −0.125, 0.0625) and waits
/// for its full frame; returns the frame's generation.
fn move_observer(port: u16) -> u64 {
    let event_json = r#"{"t": 1.5, "x": 0.25, "y": -0.125, "z": 0.0625}"#;
    let (status, body) = http(port, "POST", "/api/explore/event", event_json);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    let generation = json(&body)["generation"].as_u64().unwrap();
    let frame = full_frame(port, Some(generation));
    assert_eq!(frame["level"], "full", "{frame}");
    generation
}

/// The scene of [`origin_scene`] with its observer at the event of [`move_observer`], and
/// `camera` (the `[camera]` table's lines) in place of its own, as `name` in `dir`.
fn moved_scene(dir: &Path, name: &str, camera: Option<&str>) -> std::path::PathBuf {
    let observer = "time = 1.5\nposition = { x = 0.25, y = -0.125, z = 0.0625 }";
    let mut text = scene_text(observer);
    if let Some(camera) = camera {
        let start = text.find("[camera]").unwrap();
        let end = text.find("[trace]").unwrap();
        text.replace_range(start..end, &format!("[camera]\n{camera}\n\n"));
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Issue 24: Save PNG, overlays and `/api/info` answered from the first coarse frame at the
/// scene's start event: after a move, Save PNG gave the start picture at coarse size (12×2
/// for a 48×8 frame) and the overlay never had the full frame's size. Now they answer for the
/// frame the request names (the one on screen), at its size.
#[test]
fn saved_pictures_overlays_and_info_belong_to_the_frame_on_screen() {
    let dir = tempfile::tempdir().unwrap();
    let scene = origin_scene(dir.path());
    let (_server, port) = explore(&scene);
    let generation = move_observer(port);
    let shown = format!("?generation={generation}&level=full");

    let (status, body) = http(port, "GET", &format!("/api/info{shown}"), "");
    assert_eq!(status, 200);
    let info = json(&body);
    assert_eq!(
        (info["width"].as_u64(), info["height"].as_u64()),
        (Some(48), Some(8)),
        "{info}"
    );
    assert_eq!(info["observer_time"], 1.5, "{info}");
    let defaults = info["defaults"].clone();
    // Without a name: the frame the server opened on (whose channels /api/gpu serves to a
    // page that has taken no traced frame yet), at the start event: its coarse frame, or its
    // full one where that was done before the server took its first frame (Explorer::
    // first_frame takes the newest of the first request; seen once in CI).
    let (_, body) = http(port, "GET", "/api/info", "");
    let first = json(&body);
    assert_eq!(first["observer_time"].as_f64(), Some(0.0), "{first}");
    assert!(
        [Some(12), Some(48)].contains(&first["width"].as_u64()),
        "{first}"
    );
    let settings = defaults.to_string();

    // Save PNG: godel render of the moved observer, then godel shade, pixel for pixel.
    let moved = moved_scene(dir.path(), "moved.toml", None);
    let out = dir.path().join("out");
    let o = common::render(&moved, &out, &["-q", "--method", "exact"]);
    assert!(o.status.success(), "{o:?}");
    let shaded = dir.path().join("shaded.png");
    let o = common::shade(&out.join("static-sphere.exr"), &shaded, &[]);
    assert!(o.status.success(), "{o:?}");
    let expected = png_pixels(&std::fs::read(&shaded).unwrap());
    assert_eq!((expected.0, expected.1), (48, 8));
    let (status, body) = http(port, "POST", &format!("/api/png{shown}"), &settings);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    assert_eq!(png_pixels(&body), expected);
    // The coarse frame of that event, named, at its own size.
    let coarse = format!("?generation={generation}&level=coarse");
    let (status, body) = http(port, "POST", &format!("/api/png{coarse}"), &settings);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    assert_eq!(png_pixels(&body).0, 12);

    // The overlay (orientation marks) has the size of the frame on screen.
    let mut marked = defaults.clone();
    marked["grid"] = serde_json::Value::Bool(true);
    let path = format!("/api/overlay{shown}");
    let (status, body) = http(port, "POST", &path, &marked.to_string());
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    let layer = image::load_from_memory(&body).unwrap();
    assert_eq!((layer.width(), layer.height()), (48, 8));

    // A frame that is gone is said to be gone, not answered from another.
    let (status, _) = http(port, "POST", "/api/png?generation=1&level=full", &settings);
    assert_eq!(status, 410);
    let (status, _) = http(
        port,
        "POST",
        &format!("/api/png?generation={generation}"),
        &settings,
    );
    assert_eq!(status, 400);
}

/// Issue 24: with `--sphere`, looked pictures were made from the first coarse sphere at the
/// start event. Now a looked PNG of the frame on screen is `godel look` then `godel shade` of
/// `godel render` of the sphere seen by the moved observer, pixel for pixel.
#[test]
fn looked_pictures_belong_to_the_sphere_on_screen() {
    let dir = tempfile::tempdir().unwrap();
    let scene = origin_scene(dir.path());
    let (_server, url) = start_server_with("explore", &scene, dir.path(), &["--sphere", "32"]);
    let port = port_of(&url);
    let generation = move_observer(port);
    let (_, body) = http(port, "GET", "/api/info", "");
    let settings = json(&body)["defaults"].clone();
    let view = serde_json::json!({
        "camera": {"kind": "panorama", "h_fov_deg": 360.0, "v_fov_deg": 90.0, "width": 48, "height": 12},
        "forward": [1.0, 0.0, 0.0],
        "up": [0.0, 0.0, 1.0],
        "velocity": {"speed": 0.5, "direction": [0.0, 1.0, 0.0]},
    });
    let request = serde_json::json!({ "settings": settings, "view": view }).to_string();
    let path = format!("/api/look/png?generation={generation}&level=full");
    let (status, served) = http(port, "POST", &path, &request);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&served));

    let sphere = moved_scene(
        dir.path(),
        "sphere.toml",
        Some("kind = \"sphere\"\nwidth = 32\nheight = 16"),
    );
    let out = dir.path().join("out");
    let o = common::render(&sphere, &out, &["-q", "--method", "exact"]);
    assert!(o.status.success(), "{o:?}");
    let view_exr = dir.path().join("view.exr");
    let look = common::godel(&[
        "look",
        out.join("static-sphere.exr").to_str().unwrap(),
        "--camera",
        "panorama",
        "--h-fov",
        "360",
        "--v-fov",
        "90",
        "--width",
        "48",
        "--height",
        "12",
        "--forward",
        "1,0,0",
        "--up",
        "0,0,1",
        "--velocity",
        "0.5,0,1,0",
        "-o",
        view_exr.to_str().unwrap(),
    ]);
    assert!(look.status.success(), "{look:?}");
    let shaded = dir.path().join("view-shaded.png");
    let o = common::shade(&view_exr, &shaded, &[]);
    assert!(o.status.success(), "{o:?}");
    let expected = png_pixels(&std::fs::read(&shaded).unwrap());
    let colours: std::collections::BTreeSet<&[u8]> = expected.2.chunks(3).collect();
    assert!(
        colours.len() > 2,
        "the view shows the ball: {} colours",
        colours.len()
    );
    assert_eq!(png_pixels(&served), expected);
}

/// Issue 36: a recording of two keyframes an hour apart (86,401 frames, 0.6 KB) cost seconds
/// of CPU each (its scene parsed again for every frame), on the slots that shading and the
/// other routes share: one more of them than the machine has cores kept
/// `/api/explore/view-keyframe` waiting 16–57 s. Now recordings are made into scripts on a
/// slot of their own, each frame checked in a small part of the scene: the other routes
/// answer at once (a bound of a second where they take milliseconds), and the recordings
/// still get their scripts (or 503 once too many wait).
#[test]
fn recordings_of_an_hour_do_not_hold_up_the_other_routes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = origin_scene(dir.path());
    let (_server, port) = explore(&scene);
    let (status, body) = http(port, "GET", "/api/explore/view", "");
    assert_eq!(status, 200);
    let view = json(&body)["view"].clone();
    let keyframes =
        [(0, &view), (3600, &view)].map(|(s, v)| serde_json::json!({"seconds": s, "view": v}));
    let recording = serde_json::json!({ "keyframes": keyframes }).to_string();
    // As many as the server has slots for shading (one per core), and one more.
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let recorders: Vec<_> = (0..=cores)
        .map(|_| {
            let recording = recording.clone();
            std::thread::spawn(move || http(port, "POST", "/api/explore/record", &recording))
        })
        .collect();
    // Time for every recording to arrive and start (milliseconds here).
    std::thread::sleep(Duration::from_millis(500));
    let started = std::time::Instant::now();
    let path = "/api/explore/view-keyframe?frame=0";
    let (status, body) = http(port, "POST", path, &view.to_string());
    let waited = started.elapsed();
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    assert!(
        waited < Duration::from_secs(1),
        "view-keyframe took {waited:?}"
    );
    let mut scripts = 0;
    for recorder in recorders {
        let (status, body) = recorder.join().unwrap();
        let text = String::from_utf8_lossy(&body);
        match status {
            200 => {
                assert!(text.contains("frames = 86401"), "{text}");
                scripts += 1;
            }
            503 => assert!(text.contains("busy"), "{text}"),
            _ => panic!("record answered {status}: {text}"),
        }
    }
    assert!(scripts > 0, "no recording got its script");
}

/// Issue 36: explore's refusals named `velocity:` without the route's name and printed 1e308
/// with its 309 digits (the source's and the scene's checks behind the routes), and a bad
/// render number in `/api/explore/exact/N/FILE` was answered in plain text. Now each names
/// the field as the request wrote it, in short, as JSON.
#[test]
fn explore_refusals_name_what_the_request_wrote_in_short() {
    let dir = tempfile::tempdir().unwrap();
    let scene = origin_scene(dir.path());
    let (_server, port) = explore(&scene);
    let (status, body) = http(port, "GET", "/api/explore/view", "");
    assert_eq!(status, 200);
    let mut view = json(&body)["view"].clone();
    view["camera"]["h_fov_deg"] = 1e308.into();
    let fov = "view.camera.h_fov_deg: must be in (0, 360] degrees, got 1e308";
    let step = r#"{"time": 1, "position": {"x": 0, "y": 0, "z": 0},
        "velocity": {"speed": 1e308, "direction": [1, 0, 0]}, "tau": 2}"#;
    for (path, body, want) in [
        ("/api/explore/view-keyframe", view.to_string(), fov),
        ("/api/explore/exact", view.to_string(), fov),
        (
            "/api/explore/move",
            step.to_string(),
            "move.velocity: speed 1e308 must be in [0, 1)",
        ),
    ] {
        let (status, answer) = http(port, "POST", path, &body);
        assert_eq!(status, 400, "{path}");
        let error = json(&answer)["error"].as_str().unwrap().to_string();
        assert!(error.starts_with(want), "{path}: {error}");
    }
    let (status, answer) = http(port, "GET", "/api/explore/exact/abc/png", "");
    assert_eq!(status, 400);
    let error = json(&answer)["error"].as_str().unwrap().to_string();
    assert!(error.starts_with("exact: `abc` is not"), "{error}");
}

/// A Gödel-type member (issue 34) explores as Gödel's universe does: the server's full frame
/// comes, and the page's kernel input is the member's (its defines name a member, its
/// uniforms the member's constants and observer isometry). A ball falling fast enough to escape a
/// causal member is the one scene the kernel refuses, with the sentence that says why and that
/// the server traces it on the CPU (the page shows it and keeps the server's frames).
#[test]
fn a_godel_type_member_explores_on_the_kernel_and_an_escaping_ball_on_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("member.toml");
    let text = scene_text("time = 0.0\nposition = { x = 0.3, y = 0.0, z = 0.0 }").replace(
        "metric = \"godel\"\na = 1.0",
        "metric = \"godel-type\"\nm2 = 0.5\nomega = 0.7071067811865476",
    );
    assert!(text.contains("godel-type"));
    std::fs::write(&scene, &text).unwrap();
    let (server, port) = explore(&scene);
    let frame = full_frame(port, None);
    assert_eq!(frame["level"], "full", "{frame}");
    let (status, body) = http(port, "GET", "/api/gpu/input?draw_buffers=4", "");
    let input = json(&body);
    assert_eq!(status, 200, "{input}");
    let defines = input["defines"].as_str().unwrap();
    assert!(defines.contains("#define MEMBER 1"), "{defines}");
    assert_eq!(input["uniforms"]["member"][0], 0.5, "{input}");
    assert!(defines.contains("#define GODEL 0"), "{defines}");
    // The observer's isometry is the member's: its base coordinate of x = 0.3, ζ = G(m²ρ²)x
    // with G = tanh(mρ/2)/(mρ/2) < 1 (Gödel's disc coordinate would be 0.3/√(0.09 + 4a²)).
    let to = input["uniforms"]["obs_to"][0].as_f64().unwrap();
    let h = 0.5 * 0.5f64.sqrt() * 0.3;
    assert!((to - 0.3 * h.tanh() / h).abs() < 1e-6, "{to}");
    drop(server);
    // m² = 6Ω², causal; at 0.9 c across the axis Λ = γ²(Ω² − (m²/4)v²) < 0: the ball escapes.
    let escaping = text.replace("m2 = 0.5", "m2 = 3.0").replace(
        "[[object]]",
        "[[object]]\nname = \"fast\"\nradius = 0.05\nmotion = { kind = \"geodesic\", time = 0.0, \
         position = { x = -0.5, y = 0.0, z = 0.0 }, speed = 0.9, direction = [0, 1, 0] }\n\n[[object]]",
    );
    std::fs::write(&scene, escaping).unwrap();
    let (_server, port) = explore(&scene);
    let (status, body) = http(port, "GET", "/api/gpu/input?draw_buffers=4", "");
    let body = String::from_utf8_lossy(&body);
    assert_eq!(status, 400, "{body}");
    assert!(body.contains("escape") && body.contains("CPU"), "{body}");
}
