//! `godel merge PART… -o DIR`: joins the part files of `godel render --part i/N` into
//! `DIR/<name>.exr` and `DIR/<name>.png` (or the pair `-o x.exr` names, `out_pair`), the very
//! files a single run writes. Parts of
//! different renders, a missing or repeated part, or overlapping parts are refused
//! (`render::part::merge`), and nothing is written then.

use crate::inputs::Inputs;
use crate::out_pair::OutPair;
use crate::output::{prepare, write_data_and_preview};
use clap::Args;
use render::part::{merge, read_part};
use scene::Scene;
use std::path::PathBuf;

#[derive(Args, Debug)]
#[command(after_help = "\
Limits: each part a regular file of at most 8 GiB. The EXR and the PNG are renamed together \
at the end, as by `godel render`.")]
pub struct MergeArgs {
    /// The part files (`<name>.part-i-of-N.exr`), all N of them, in any order.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output FOLDER (created if missing) that receives NAME.exr and NAME.png, or the file
    /// x.exr or x.png: both are written, the other beside it (as `render -o`).
    #[arg(short, long, default_value = "out", value_name = "FOLDER|FILE")]
    pub output: PathBuf,
    /// Orientation marks on the preview: azimuth/elevation grid with labelled ticks.
    #[arg(long)]
    pub grid: bool,
}

pub fn run(args: MergeArgs) -> anyhow::Result<()> {
    let target = OutPair::parse("--output", &args.output, false)?;
    let parts = args
        .parts
        .iter()
        .map(|p| read_part(p))
        .collect::<Result<Vec<_>, _>>()?;
    let data = merge(&parts)?;
    // The preview needs the scene's textures: the scene text travels in the data file,
    // its path (for relative image paths) in the part attributes.
    let first = &parts[0];
    let scene = if first.scene_path.is_empty() {
        Scene::builtin()
    } else {
        // A damaged part (exit 1), not a usage error.
        Scene::from_str(&data.header.scene_text, &first.scene_path)
            .map_err(|e| anyhow::anyhow!("the scene embedded in the parts: {e}"))?
    };
    prepare("--output", target.folder(), &target.names(&scene.name))?;
    let (exr, png) = target.files(&scene.name);
    let mut inputs = Inputs::new();
    for part in &args.parts {
        inputs.add("a part file", part);
    }
    inputs.refuse_outputs_over_inputs("--output", &[exr.clone(), png.clone()])?;
    write_data_and_preview(&scene, &data, &exr, &png, args.grid)
}
