//! `viewer`: the live web viewer behind `godel view` (docs/guide/src/viewer.md). A local axum
//! server holds one data file in memory; the page (embedded in the binary) fetches the file's
//! channels once and shades them on the GPU with WebGL2 shaders that reproduce the `shade`
//! crate's rule, so every control, turn, zoom and boost redraws within a frame. The server
//! stays the source of the data, of hover records, and of saved pictures and keyframes (shaded
//! by the `shade` crate, after the `look` crate for a turned or boosted view).
//!
//! - [`ViewerState`]: the loaded data file, shading, pixel records, keyframes; image textures
//!   only from the data file's folder and [`ViewerOptions::texture_folders`]; of one eye of a
//!   stereo pair, the other eye's file beside it too ([`state::Stereo`]).
//! - [`router`]: the routes (see [`routes`], [`gpu_routes`] and [`look_routes`] for the
//!   tables), [`serve`]: runs them within the bounds of [`server`] (header read timeout,
//!   connection cap, shutdown with a deadline).
//! - [`Access`]: which `Host` names the server; [`guard`] checks Host, Origin and JSON bodies.
//! - [`WorkLimit`]: the bound on concurrent shading.
//! - [`wire`]: the binary format of the arrays the page uploads as textures; [`gpu`]: what
//!   they hold (channels, textures, black-body tables).
//! - The settings the page sends are `shade::ShadeSettings` as JSON.
//! - [`kernel_routes`]: the exact tracer's GPU kernel and its input, for the page to trace a
//!   frame itself.
//! - [`explore`], [`explore_routes`]: explore mode (`godel explore`), frames re-traced for a
//!   moved observer by a [`explore::FrameSource`]; [`keep`], [`keep_routes`]: its *Render
//!   exactly* and *Record* (made by a [`keep::Keeper`]); [`page_check`]: the flying page's
//!   samples held to the CPU exact tracer before its GPU is trusted.

pub mod api_error;
mod assets;
pub mod encode;
pub mod explore;
pub mod explore_routes;
pub mod gpu;
pub mod gpu_routes;
pub mod guard;
pub mod keep;
pub mod keep_routes;
pub mod kernel_routes;
pub mod limit;
pub mod look_routes;
pub mod page_check;
mod responses;
pub mod routes;
pub mod server;
pub mod state;
pub mod view;
pub mod wire;

use std::sync::Arc;

pub use api_error::ApiError;
pub use guard::{Access, MAX_BODY_BYTES};
pub use limit::WorkLimit;
pub use routes::router;
pub use state::{LoadError, PixelInfo, ViewerOptions, ViewerState};

/// Serves the viewer on `listener` until Ctrl-C (or SIGTERM), answering what `access`
/// allows, within [`server::Bounds::for_this_process`].
pub async fn serve(
    listener: tokio::net::TcpListener,
    state: Arc<ViewerState>,
    access: Access,
) -> std::io::Result<()> {
    let app = router(state, access);
    server::serve(
        listener,
        app,
        server::Bounds::for_this_process(),
        shutdown(),
    )
    .await
}

/// Resolves on Ctrl-C or SIGTERM.
async fn shutdown() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => {}
        _ = term => {}
    }
}

/// Serves the viewer on an already bound `listener` on a new tokio runtime, blocking until
/// Ctrl-C or SIGTERM: the command line needs no async code of its own. Requests must name
/// the address listened on ([`Access::listening_on`]).
pub fn run(listener: std::net::TcpListener, state: Arc<ViewerState>) -> std::io::Result<()> {
    run_app(listener, |access| router(state, access))
}

/// [`run`] for any app built from the [`Access`] of `listener` (explore mode:
/// [`explore_routes::router`]). Returns within about a second of the signal, whatever the
/// clients do: shading still under way on blocking threads is not waited for.
pub fn run_app(
    listener: std::net::TcpListener,
    app: impl FnOnce(Access) -> axum::Router,
) -> std::io::Result<()> {
    let access = Access::listening_on(listener.local_addr()?);
    listener.set_nonblocking(true)?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        // Few I/O threads: shading runs on rayon's pool and tokio's blocking threads.
        .worker_threads(2)
        .enable_all()
        .build()?;
    let served = runtime.block_on(async move {
        let listener = tokio::net::TcpListener::from_std(listener)?;
        let bounds = server::Bounds::for_this_process();
        server::serve(listener, app(access), bounds, shutdown()).await
    });
    runtime.shutdown_timeout(std::time::Duration::from_millis(100));
    served
}
