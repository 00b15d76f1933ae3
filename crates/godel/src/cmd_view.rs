//! `godel view DATA.exr [--port P] [--host H] [--textures DIR]…`: the live web viewer. Loads
//! the data file (errors before anything is served), binds the port (0: any free port),
//! prints `godel view: serving http://HOST:PORT/` on stdout and serves until Ctrl-C; the
//! server and the page (which shades on the GPU with WebGL2) live in the `viewer` crate.
//! Image textures come only from the data file's folder and the `--textures` folders;
//! requests must name localhost (or the `--host` address).

use std::io::Write;
use std::net::{IpAddr, SocketAddr, TcpListener};
use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use clap::Args;

use crate::args::usage;

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Data file (.exr) written by `godel render` (a full sphere, `[camera] kind = "sphere"`,
    /// can be looked around in any direction and at any velocity).
    pub data: PathBuf,
    /// Port to serve on; 0 picks a free one.
    #[arg(long, default_value_t = 8737)]
    pub port: u16,
    /// Address to listen on (the default serves this machine only). Requests must name
    /// localhost or this address; 0.0.0.0 or :: accepts any IP address.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,
    /// A folder image textures may come from, besides the data file's own (repeatable).
    #[arg(long, value_name = "DIR")]
    pub textures: Vec<PathBuf>,
}

pub fn run(args: ViewArgs) -> anyhow::Result<()> {
    let ip: IpAddr = args.host.parse().map_err(|_| {
        usage(
            "--host",
            format!("'{}' is not an IP address (e.g. 127.0.0.1)", args.host),
        )
    })?;
    let options = viewer::ViewerOptions {
        texture_folders: args.textures.clone(),
        ..viewer::ViewerOptions::default()
    };
    let state = viewer::ViewerState::load_with(&args.data, options).map_err(|e| match e {
        viewer::LoadError::TextureFolder(e) => usage("--textures", e.to_string()),
        other => other.into(),
    })?;
    let wanted = SocketAddr::new(ip, args.port);
    let listener = TcpListener::bind(wanted).map_err(|e| match e.kind() {
        std::io::ErrorKind::AddrInUse => usage(
            "--port",
            format!("{wanted} is already in use; choose another port, or 0 for any free one"),
        ),
        _ => anyhow::Error::new(e).context(format!("cannot listen on {wanted}")),
    })?;
    let addr = listener
        .local_addr()
        .context("cannot read the bound address")?;
    let mut stdout = std::io::stdout();
    writeln!(stdout, "godel view: serving http://{addr}/")?;
    stdout.flush()?;
    let folders: Vec<String> = state
        .texture_folders()
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    eprintln!(
        "{} ({}×{}); image textures from {}; press Ctrl-C to stop",
        args.data.display(),
        state.data.picture_size().0,
        state.data.picture_size().1,
        folders.join(", ")
    );
    viewer::run(listener, Arc::new(state)).context("the viewer's server failed")
}
