//! `godel view DATA.exr [--port P] [--host H] [--textures DIR]…`: the live web viewer. Loads
//! the data file (errors before anything is served), binds the port (0: any free port),
//! prints `godel view: serving http://HOST:PORT/` on stdout and serves until Ctrl-C; the
//! server and the page (which shades on the GPU with WebGL2) live in the `viewer` crate.
//! Image textures come only from the data file's folder and the `--textures` folders;
//! requests must name localhost (or the `--host` address).

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use clap::Args;

use crate::serve::{load_error, ServeArgs};

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Data file (.exr) written by `godel render` (a full sphere, `[camera] kind = "sphere"`,
    /// can be looked around in any direction and at any velocity).
    pub data: PathBuf,
    #[command(flatten)]
    pub serve: ServeArgs,
}

pub fn run(args: ViewArgs) -> anyhow::Result<()> {
    let ip = args.serve.ip()?;
    let state =
        viewer::ViewerState::load_with(&args.data, args.serve.options()).map_err(load_error)?;
    let listener = args.serve.listen(ip, "view")?;
    let folders: Vec<String> = state
        .texture_folders()
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    // One eye of a stereo pair: say whether the other is there to be shown beside it.
    let stereo = match state.stereo() {
        None => String::new(),
        Some(s) => match &s.partner {
            Some(_) => format!(
                "; the {} eye of a stereo pair ({})",
                s.eye.name(),
                s.layout.name()
            ),
            None => format!(
                "; the {} eye of a stereo pair, the other eye's file missing",
                s.eye.name()
            ),
        },
    };
    eprintln!(
        "{} ({}×{}{stereo}); image textures from {}; press Ctrl-C to stop",
        args.data.display(),
        state.data.picture_size().0,
        state.data.picture_size().1,
        folders.join(", ")
    );
    viewer::run(listener, Arc::new(state)).context("the viewer's server failed")
}
