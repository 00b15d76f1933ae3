//! Helpers shared by the CLI tests: running `godel` (`render` in particular), a path as an
//! argument, reading a PNG's pixels, reading a command's standard error, a
//! small lit scene (parts and MPI ranks), writing it, running under a time limit, reading the
//! R, G, B planes of a picture EXR, a data file's records as text.

use std::path::{Path, PathBuf};
use std::process::Output;

pub use testkit::stderr;

/// The `godel` binary of this package.
pub const GODEL: &str = env!("CARGO_BIN_EXE_godel");

/// Runs the `godel` binary of this package with `args` to its end.
pub fn godel(args: &[&str]) -> Output {
    testkit::run(GODEL, args)
}

/// Runs `godel` with `args` and asserts that it succeeds; returns its output.
pub fn godel_ok(args: &[&str]) -> Output {
    let o = godel(args);
    assert!(o.status.success(), "godel {args:?}: {}", stderr(&o));
    o
}

/// Runs `godel render SCENE -o OUT` followed by `extra` to its end.
pub fn render(scene: &Path, out: &Path, extra: &[&str]) -> Output {
    godel(&[&["render", path_arg(scene), "-o", path_arg(out)], extra].concat())
}

/// Runs `godel shade DATA -o OUT` followed by `extra` to its end.
pub fn shade(data: &Path, out: &Path, extra: &[&str]) -> Output {
    godel(&[&["shade", path_arg(data), "-o", path_arg(out)], extra].concat())
}

/// The arguments of `godel geodesic` from the origin at t = 0 along +x, then `extra`.
pub fn geodesic_along_x<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    [&["geodesic", "--at", "0,0,0,0", "--dir", "1,0,0"], extra].concat()
}

/// Asserts that each of `files` is the same, byte for byte, in folders `a` and `b`
/// (`between` names the two runs in the message).
pub fn assert_same_files(a: &Path, b: &Path, files: &[&str], between: &str) {
    for file in files {
        let (x, y) = (std::fs::read(a.join(file)), std::fs::read(b.join(file)));
        assert!(x.unwrap() == y.unwrap(), "{file} differs between {between}");
    }
}

/// A path as a command-line argument (the tests' paths are UTF-8).
pub fn path_arg(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The pixels of a picture file (a PNG) as 8-bit RGB.
pub fn png(path: &Path) -> image::RgbImage {
    image::open(path).unwrap().to_rgb8()
}

/// A small scene with a falling, textured ball (several images, varied records) lit by a
/// point light (a `light_0` channel), 6×3 tiles of 16 pixels with ragged edges.
/// `name` names the output files; `max_past` tells two scenes apart.
pub fn lit_scene_text(name: &str, max_past: f64) -> String {
    testkit::axis_panorama(
        name,
        90,
        37,
        max_past,
        r#"[[object]]
name = "ball"
radius = 0.25
texture = { kind = "checker", rows = 4, cols = 8 }
motion = { kind = "geodesic", time = -1.0, position = { x = -0.8, y = 0.2, z = 0.0 }, speed = 0.6, direction = [0, 1, 0] }
[[light]]
position = { x = 1.0, y = 1.0, z = 0.0 }
color = [1.0, 1.0, 1.0]
power = 12.0
"#,
    )
}

pub fn write_scene(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// Runs `godel sequence SCRIPT -q`, killed and failed after `limit`.
pub fn sequence_within(script: &Path, limit: std::time::Duration) -> Output {
    run_within(
        std::process::Command::new(env!("CARGO_BIN_EXE_godel")).args([
            "sequence",
            script.to_str().unwrap(),
            "-q",
        ]),
        limit,
    )
}

/// Runs `cmd` to its end, or kills it after `limit` and fails the test: the command must
/// never hang (issue 10). Standard output and error are collected as they come, so a chatty
/// command cannot block on a full pipe.
pub fn run_within(cmd: &mut std::process::Command, limit: std::time::Duration) -> Output {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the command");
    let drain = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            bytes
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let started = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            let err = String::from_utf8_lossy(&err.join().unwrap()).into_owned();
            panic!("{cmd:?} did not end within {limit:?} (killed); stderr: {err}");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    Output {
        status,
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    }
}

/// Every file in `dir` (none when it does not exist), sorted.
/// The name of the manifest in which `godel sequence` records the files it writes.
pub const MANIFEST: &str = ".godel-sequence";

/// Records the files `names` of `dir` in its sequence manifest, as an earlier sequence that
/// wrote them would have (size and modification time, `crates/godel/src/manifest.rs`).
pub fn record_as_sequence_output(dir: &Path, names: &[&str]) {
    use std::io::Write;
    let mut lines = String::new();
    for name in names {
        let meta = std::fs::metadata(dir.join(name)).unwrap();
        let ns = meta
            .modified()
            .unwrap()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos();
        lines.push_str(&format!("{} {ns} {name}\n", meta.len()));
    }
    std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(dir.join(MANIFEST))
        .unwrap()
        .write_all(lines.as_bytes())
        .unwrap();
}

pub fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = match std::fs::read_dir(dir) {
        Ok(entries) => entries
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect(),
        Err(_) => vec![],
    };
    v.sort();
    v
}

/// The R, G, B planes of an OpenEXR file, read with the exr crate.
pub fn read_rgb(path: &Path) -> Vec<[f32; 3]> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_file(path)
        .unwrap();
    let layer = &image.layer_data[0];
    let plane = |name: &str| -> Vec<f32> {
        let ch = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name)
            .unwrap_or_else(|| panic!("channel {name}"));
        ch.sample_data.values_as_f32().collect()
    };
    let names: Vec<String> = layer
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    assert_eq!(names, ["B", "G", "R"]);
    let (r, g, b) = (plane("R"), plane("G"), plane("B"));
    (0..r.len()).map(|i| [r[i], g[i], b[i]]).collect()
}

/// Shades the data file `data` with the lit texture layers into `STEM.exr` (linear RGB) and
/// `STEM.png` (for display) in `dir`; asserts both runs succeed and returns the two paths.
pub fn shade_lit_pair(data: &Path, dir: &Path, stem: &str) -> (PathBuf, PathBuf) {
    let (exr, png) = (
        dir.join(format!("{stem}.exr")),
        dir.join(format!("{stem}.png")),
    );
    for out in [&exr, &png] {
        let o = shade(data, out, &["--shader", "texture,light"]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    (exr, png)
}

/// Asserts that `o` is a refusal of bad input: exit status 2, one line of stderr holding
/// every needle, and nothing written at `no_output`.
pub fn assert_refused(o: &Output, needles: &[&str], no_output: &Path) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert_eq!(e.lines().count(), 1, "{e}");
    for n in needles {
        assert!(e.contains(n), "expected {n:?} in {e}");
    }
    assert!(
        !no_output.exists(),
        "{} written for bad input",
        no_output.display()
    );
}

/// Asserts that `o` is a refusal of a command-line flag: exit code 2 and one
/// `error: FLAG: …` line.
pub fn assert_usage(o: &Output, flag: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.starts_with(&format!("error: {flag}: ")), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// A running `godel view` or `godel explore`, killed when dropped.
pub struct Server(std::process::Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts `godel COMMAND FILE --port 0` in `cwd`; returns it and the URL it printed
/// (`http://127.0.0.1:PORT/`).
pub fn start_server(command: &str, file: &Path, cwd: &Path) -> (Server, String) {
    start_server_with(command, file, cwd, &[])
}

/// [`start_server`] with `extra` arguments after the port.
pub fn start_server_with(
    command: &str,
    file: &Path,
    cwd: &Path,
    extra: &[&str],
) -> (Server, String) {
    use std::io::BufRead;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_godel"))
        .args([command, file.to_str().unwrap(), "--port", "0"])
        .args(extra)
        .current_dir(cwd)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::inherit())
        .spawn()
        .unwrap_or_else(|e| panic!("start godel {command}: {e}"));
    let stdout = child.stdout.take().unwrap();
    let server = Server(child);
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = std::io::BufReader::new(stdout).read_line(&mut line);
        let _ = send.send(line);
    });
    // A deadline against hanging forever, not a speed check.
    let line = receive
        .recv_timeout(std::time::Duration::from_secs(120))
        .unwrap_or_else(|_| panic!("godel {command} printed no URL"));
    let url = line
        .trim()
        .strip_prefix(&format!("godel {command}: serving "))
        .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
        .to_string();
    assert!(
        url.starts_with("http://127.0.0.1:") && url.ends_with('/'),
        "{url}"
    );
    (server, url)
}

/// The port of a URL `http://HOST:PORT/` printed by [`start_server`].
pub fn port_of(url: &str) -> u16 {
    url.trim_end_matches('/')
        .rsplit(':')
        .next()
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no port in {url:?}"))
}

/// The records of a data file, every bit of every field (NaN included) as text.
pub fn records(path: &Path) -> String {
    let data = datafile::DataFile::read(path).unwrap();
    format!("{:?} {:?}", data.records, data.lights)
}
