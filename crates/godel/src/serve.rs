//! What `godel view` and `godel explore` share to start the viewer's server: the `--port`,
//! `--host` and `--textures` flags, the viewer options they give, and binding the port
//! (0: any free one) with `godel COMMAND: serving http://HOST:PORT/` printed on stdout.

use std::io::Write;
use std::net::{IpAddr, SocketAddr, TcpListener};
use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use crate::args::usage;

#[derive(Args, Debug)]
pub struct ServeArgs {
    /// Port to serve on; 0 picks a free one.
    #[arg(long, default_value_t = 8737)]
    pub port: u16,
    /// Address to listen on (the default serves this machine only). Requests must name
    /// localhost or this address; 0.0.0.0 or :: accepts any IP address.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,
    /// A folder image textures may come from, besides the input file's own (repeatable).
    #[arg(long, value_name = "DIR")]
    pub textures: Vec<PathBuf>,
}

impl ServeArgs {
    /// The `--host` address, checked before any work is done.
    pub fn ip(&self) -> anyhow::Result<IpAddr> {
        self.host.parse().map_err(|_| {
            usage(
                "--host",
                format!("'{}' is not an IP address (e.g. 127.0.0.1)", self.host),
            )
        })
    }

    /// The viewer's options for these flags.
    pub fn options(&self) -> viewer::ViewerOptions {
        viewer::ViewerOptions {
            texture_folders: self.textures.clone(),
            ..viewer::ViewerOptions::default()
        }
    }

    /// Binds `ip` and the port and says where `godel COMMAND` serves.
    pub fn listen(&self, ip: IpAddr, command: &str) -> anyhow::Result<TcpListener> {
        let wanted = SocketAddr::new(ip, self.port);
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
        writeln!(stdout, "godel {command}: serving http://{addr}/")?;
        stdout.flush()?;
        Ok(listener)
    }
}

/// A viewer that could not load, as a located error (a bad `--textures` folder is a usage error).
pub fn load_error(e: viewer::LoadError) -> anyhow::Error {
    match e {
        viewer::LoadError::TextureFolder(e) => usage("--textures", e.to_string()),
        other => other.into(),
    }
}
