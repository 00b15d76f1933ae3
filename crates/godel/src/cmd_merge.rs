//! `godel merge PART… -o DIR`: joins the part files of `godel render --part i/N` into
//! `DIR/<name>.exr` and `DIR/<name>.png`, the very files a single run writes. Parts of
//! different renders, a missing or repeated part, or overlapping parts are refused
//! (`render::part::merge`), and nothing is written then.

use crate::inputs::Inputs;
use crate::output::write_outputs;
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
    /// Output FOLDER (created if missing): receives NAME.png and NAME.exr; a path ending in
    /// .png or .exr is refused.
    #[arg(short, long, default_value = "out", value_name = "FOLDER")]
    pub output: PathBuf,
    /// Orientation marks on the preview: azimuth/elevation grid with labelled ticks.
    #[arg(long)]
    pub grid: bool,
}

pub fn run(args: MergeArgs) -> anyhow::Result<()> {
    crate::output::check_folder("--output", &args.output)?;
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
    let mut inputs = Inputs::new();
    for part in &args.parts {
        inputs.add("a part file", part);
    }
    let outputs = crate::output::output_names(&scene).map(|n| args.output.join(n));
    inputs.refuse_outputs_over_inputs("--output", &outputs)?;
    write_outputs(&scene, &data, &args.output, args.grid)
}
