//! Helpers of the browser tests (browser.rs): rendering a scene with `godel render`,
//! serving it with `godel view --port 0` (or a scene with `godel explore --port 0`), running a playwright-core script of tests/browser
//! against Debian's chromium, and reading the raw pictures the scripts save.

use std::path::{Path, PathBuf};
use std::process::Command;

pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

pub fn chromium() -> PathBuf {
    std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"))
}

/// Fails (never skips) when the browser or the npm packages are missing.
pub fn require_browser_tools() {
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

/// Writes `text` as `dir/NAME.toml`, renders it quietly into `dir`; returns `dir/NAME.exr`.
pub fn render(dir: &Path, name: &str, text: &str) -> PathBuf {
    let scene = dir.join(format!("{name}.toml"));
    std::fs::write(&scene, text).unwrap();
    let rendered = godel(&[
        "render",
        scene.to_str().unwrap(),
        "-q",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(rendered.status.success(), "{rendered:?}");
    dir.join(format!("{name}.exr"))
}

pub use crate::common::godel;
/// The `godel view` server, killed when dropped.
pub use crate::common::Server;
use crate::common::{start_server, start_server_with};

/// Starts `godel view DATA --port 0` in `cwd`; returns it and the URL it printed.
pub fn start_viewer(data: &Path, cwd: &Path) -> (Server, String) {
    start_server("view", data, cwd)
}

/// Starts `godel explore SCENE --port 0` in `cwd`, then `extra` arguments; returns it and the
/// URL it printed.
pub fn start_explore(scene: &Path, cwd: &Path, extra: &[&str]) -> (Server, String) {
    start_server_with("explore", scene, cwd, extra)
}

/// Runs `node tests/browser/SCRIPT URL OUT ARGS…` and parses the one JSON object it prints.
pub fn run_script(script: &str, url: &str, out: &Path, args: &[String]) -> serde_json::Value {
    let browser = Command::new("node")
        .current_dir(repo_root().join("tests/browser"))
        .env("CHROMIUM", chromium())
        .arg(script)
        .arg(url)
        .arg(out)
        .args(args)
        .output()
        .expect("run node (installed with chromium by scripts/test.sh)");
    assert!(
        browser.status.success(),
        "browser script {script} failed:\n{}\n{}",
        String::from_utf8_lossy(&browser.stdout),
        String::from_utf8_lossy(&browser.stderr)
    );
    serde_json::from_slice(&browser.stdout).expect("one JSON object")
}

/// Every request the browser made went to the server at `url` (the scripts record them all;
/// `blob:` URLs are the page's own downloads).
pub fn assert_only_local_requests(seen: &serde_json::Value, url: &str) {
    let requests = seen["requests"]
        .as_array()
        .expect("the script lists its requests");
    assert!(!requests.is_empty());
    for r in requests {
        let r = r.as_str().unwrap();
        assert!(
            r.starts_with(url) || r.starts_with("blob:") || r.starts_with("data:"),
            "the page asked for {r}, not the viewer's server {url}"
        );
    }
}

/// A picture the scripts saved: `NAME.rgba`, RGBA bytes top row first, with its size in
/// `NAME.json` beside (`{"width", "height", …}`); returned as RGB rows.
pub fn read_rgba(path: &Path) -> (usize, usize, Vec<u8>) {
    let meta: serde_json::Value =
        serde_json::from_slice(&std::fs::read(path.with_extension("json")).unwrap()).unwrap();
    let (w, h) = (
        meta["width"].as_u64().unwrap() as usize,
        meta["height"].as_u64().unwrap() as usize,
    );
    let rgba = std::fs::read(path).unwrap();
    assert_eq!(rgba.len(), w * h * 4, "{}", path.display());
    let rgb = rgba
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    (w, h, rgb)
}

/// How two RGB pictures differ: the largest difference of any channel, the largest among the
/// pixels that differ by at most one 8-bit step, and the pixels (col, row) that differ more.
pub struct Comparison {
    pub max: u8,
    pub within: u8,
    pub off: Vec<(usize, usize)>,
}

/// Compares two RGB pictures of `width` columns.
pub fn compare(a: &[u8], b: &[u8], width: usize) -> Comparison {
    assert_eq!(a.len(), b.len());
    let mut c = Comparison {
        max: 0,
        within: 0,
        off: Vec::new(),
    };
    for (i, (p, q)) in a.chunks_exact(3).zip(b.chunks_exact(3)).enumerate() {
        let d = (0..3).map(|k| p[k].abs_diff(q[k])).max().unwrap();
        c.max = c.max.max(d);
        if d > 1 {
            c.off.push((i % width, i / width));
        } else {
            c.within = c.within.max(d);
        }
    }
    c
}
