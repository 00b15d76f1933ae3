//! The README's picture of the Gödel-type family (docs/guide/src/scenes.md, "Gödel-type
//! spacetimes"): one scene seen in several members, stacked top to bottom, each with a label.
//!
//!   cargo run --release -p godel --example family_picture -- SCENE OUT.png R1 R2 …
//!
//! Each Ri is m²/Ω²; the scene's own Ω is kept and its `m2` line replaced by Ri·Ω² (the
//! scene's text, so each member's render is exactly `godel render` of that text). Each
//! member is traced by the scene's tracer and shaded as `godel render`'s preview.

use anyhow::{bail, Context};
use image::{Rgba, RgbaImage};
use render::driver::{render, Progress};
use scene::Scene;
use shade::text::{fill, Label};
use std::path::Path;

/// At most this many members: the picture stays one README figure.
const MAX_MEMBERS: usize = 8;
/// The label band: the pictures' sky, light text.
const BAND: [u8; 3] = [12, 16, 36];
const INK: [u8; 3] = [235, 235, 235];

/// Prints the share of rays traced, every 10 %.
struct Tenths(std::sync::atomic::AtomicU64, std::sync::atomic::AtomicU64);

impl Progress for Tenths {
    fn start(&self, total: u64) {
        self.1.store(total, std::sync::atomic::Ordering::Relaxed);
    }
    fn advance(&self, n: u64) {
        use std::sync::atomic::Ordering::Relaxed;
        let total = self.1.load(Relaxed).max(1);
        let before = self.0.fetch_add(n, Relaxed);
        let (a, b) = (10 * before / total, 10 * (before + n) / total);
        if b > a {
            eprint!(" {}%", 10 * b);
        }
    }
}

/// The label of the member m² = ratio·Ω² with vorticity `omega`: its name and where its
/// closed timelike curves begin (ρ_c), in the scene's units.
fn label(ratio: f64, omega: f64) -> String {
    let m2 = match ratio {
        0.0 => "m² = 0".to_string(),
        1.0 => "m² = Ω²".to_string(),
        r => format!("m² = {r}Ω²"),
    };
    let name = match ratio {
        0.0 => " (Som–Raychaudhuri)",
        2.0 => " (Gödel’s universe)",
        _ => "",
    };
    let member = spacetime::GodelType::new(ratio * omega * omega, omega);
    let rho_c = match member.critical_radius() {
        Some(r) => format!("closed timelike curves beyond ρ_c = {r:.2}"),
        None => "no closed timelike curves".to_string(),
    };
    format!("{m2}{name}: {rho_c}")
}

/// The scene `text` rendered in the member m² = ratio·Ω², as `godel render`'s preview, with
/// the scene's Ω.
fn member(text: &str, file: &str, ratio: f64) -> anyhow::Result<(RgbaImage, f64)> {
    let base = Scene::from_str(text, file).map_err(|e| anyhow::anyhow!("{e}"))?;
    let Some(g) = base.metric.godel_type() else {
        bail!("{file}: the scene's metric must be \"godel-type\"");
    };
    let m2 = ratio * g.omega * g.omega;
    let mut lines = 0;
    let edited: String = text
        .lines()
        .map(|l| {
            if l.trim_start().starts_with("m2 ") || l.trim_start().starts_with("m2=") {
                lines += 1;
                format!("m2 = {m2:?}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    if lines != 1 {
        bail!("{file}: expected one `m2 = …` line, found {lines}");
    }
    let scene = Scene::from_str(&edited, file).map_err(|e| anyhow::anyhow!("{e}"))?;
    eprint!("{}:", label(ratio, g.omega));
    let progress = Tenths(Default::default(), Default::default());
    let (data, stats) = render(&scene, &progress)?;
    eprintln!(" ({})", stats.summary());
    let textures = shade::textures_for_scene(&scene)?;
    let rgb = shade::texture_shader::preview_with_textures(&data, &textures, &scene);
    Ok((image::DynamicImage::ImageRgb8(rgb).to_rgba8(), g.omega))
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 3 {
        bail!("usage: family_picture SCENE OUT.png R1 [R2 …] (Ri = m²/Ω²)");
    }
    let (file, out) = (&args[0], Path::new(&args[1]));
    let ratios = args[2..]
        .iter()
        .map(|r| {
            r.parse::<f64>()
                .with_context(|| format!("{r:?} is not a number"))
        })
        .collect::<anyhow::Result<Vec<f64>>>()?;
    if ratios.len() > MAX_MEMBERS {
        bail!("at most {MAX_MEMBERS} members, got {}", ratios.len());
    }
    let text = std::fs::read_to_string(file).with_context(|| format!("reading {file}"))?;
    let rendered = ratios
        .iter()
        .map(|&r| member(&text, file, r))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let (pictures, omegas): (Vec<RgbaImage>, Vec<f64>) = rendered.into_iter().unzip();
    let width = pictures.iter().map(RgbaImage::width).max().unwrap_or(0);
    let size = 16.0;
    let band = Label::new("m²", size).height() + 6;
    let height: u32 = pictures.iter().map(|p| p.height() + band as u32).sum();
    let mut sheet = RgbaImage::from_pixel(width, height, Rgba([BAND[0], BAND[1], BAND[2], 255]));
    let mut y = 0i64;
    for ((picture, &ratio), omega) in pictures.iter().zip(&ratios).zip(omegas) {
        fill(&mut sheet, 0, y, i64::from(width), band, BAND);
        Label::new(&label(ratio, omega), size).draw(&mut sheet, 6, y + 3, INK);
        y += band;
        image::imageops::overlay(&mut sheet, picture, 0, y);
        y += i64::from(picture.height());
    }
    // Written whole through a temporary file in the same folder, then renamed.
    let folder = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let tmp = tempfile::NamedTempFile::new_in(folder)?;
    image::DynamicImage::ImageRgba8(sheet)
        .to_rgb8()
        .save_with_format(tmp.path(), image::ImageFormat::Png)?;
    tmp.persist(out)?;
    eprintln!("wrote {}", out.display());
    Ok(())
}
