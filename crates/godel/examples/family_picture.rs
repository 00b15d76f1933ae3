//! The README's picture of the Gödel-type family (docs/guide/src/scenes.md, "Gödel-type
//! spacetimes"): one scene seen in several members, stacked top to bottom, each with a label.
//!
//!   cargo run --release -p godel --example family_picture -- SCENE OUT.png R1 R2 …
//!
//! Each Ri is m²/Ω²; the scene's own Ω is kept and its `m2` line replaced by Ri·Ω² (the
//! scene's text, so each member's render is exactly `godel render` of that text). Each
//! member is traced by the numeric tracer and shaded as `godel render`'s preview.

use anyhow::{bail, Context};
use image::{Rgba, RgbaImage};
use render::driver::{render, Progress};
use scene::Scene;
use shade::text::{fill, Label};
use std::path::Path;

/// At most this many members: the picture stays one README figure.
const MAX_MEMBERS: usize = 8;
const BAND: [u8; 3] = [245, 245, 245];
const INK: [u8; 3] = [20, 20, 20];

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

/// The label of the member m² = ratio·Ω².
fn label(ratio: f64) -> String {
    let name = if ratio == 0.0 {
        " (Som–Raychaudhuri)"
    } else if ratio == 2.0 {
        " (Gödel’s universe)"
    } else if ratio >= 4.0 {
        " (causal: no closed timelike curves)"
    } else {
        ""
    };
    format!("m² = {ratio}Ω²{name}")
}

fn member(text: &str, file: &str, ratio: f64) -> anyhow::Result<RgbaImage> {
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
    eprint!("{}:", label(ratio));
    let progress = Tenths(Default::default(), Default::default());
    let (data, stats) = render(&scene, &progress)?;
    eprintln!(" ({})", stats.summary());
    let textures = shade::textures_for_scene(&scene)?;
    let rgb = shade::texture_shader::preview_with_textures(&data, &textures, &scene);
    Ok(image::DynamicImage::ImageRgb8(rgb).to_rgba8())
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 3 {
        bail!("usage: family_picture SCENE OUT.png R1 [R2 …] (Ri = m²/Ω²)");
    }
    let (file, out) = (&args[0], Path::new(&args[1]));
    let ratios = args[2..]
        .iter()
        .map(|r| r.parse::<f64>().with_context(|| format!("{r:?} is not a number")))
        .collect::<anyhow::Result<Vec<f64>>>()?;
    if ratios.len() > MAX_MEMBERS {
        bail!("at most {MAX_MEMBERS} members, got {}", ratios.len());
    }
    let text = std::fs::read_to_string(file).with_context(|| format!("reading {file}"))?;
    let pictures = ratios
        .iter()
        .map(|&r| member(&text, file, r))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let width = pictures.iter().map(RgbaImage::width).max().unwrap_or(0);
    let size = 16.0;
    let band = Label::new("m²", size).height() + 6;
    let height: u32 = pictures.iter().map(|p| p.height() + band as u32).sum();
    let mut sheet = RgbaImage::from_pixel(width, height, Rgba([BAND[0], BAND[1], BAND[2], 255]));
    let mut y = 0i64;
    for (picture, &ratio) in pictures.iter().zip(&ratios) {
        fill(&mut sheet, 0, y, i64::from(width), band, BAND);
        Label::new(&label(ratio), size).draw(&mut sheet, 6, y + 3, INK);
        y += band;
        image::imageops::overlay(&mut sheet, picture, 0, y);
        y += i64::from(picture.height());
    }
    // Written whole through a temporary file in the same folder, then renamed.
    let folder = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let tmp = tempfile::NamedTempFile::new_in(folder)?;
    image::DynamicImage::ImageRgba8(sheet)
        .to_rgb8()
        .save_with_format(tmp.path(), image::ImageFormat::Png)?;
    tmp.persist(out)?;
    eprintln!("wrote {}", out.display());
    Ok(())
}
