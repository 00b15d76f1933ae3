//! The `godel` command-line tool: parses the command line with clap and dispatches each
//! subcommand to its own module (`cmd/*.rs`). `main` returns the exit code: 0 on success,
//! 2 for usage errors (from clap, or an invalid value found by validation, see
//! [`args::UsageError`]), 1 for any other failure; errors print as one line `error: ...`
//! with their cause chain, each cause said once. A closed standard output (`godel … | head`)
//! ends the command quietly with 0.
//!
//! SIGINT, SIGTERM and SIGHUP end every command but `view` and `explore` (whose server stops
//! gracefully on its own) through [`exit_on_signals`]: the temporary files of writes under way are
//! removed (`datafile::atomic`) and the process exits with 128 + the signal's number (130 for
//! Ctrl-C, 143 for SIGTERM), leaving no half-written file behind. A run that fails or is
//! interrupted also removes the output folders it created and left empty (`datafile::folders`).

mod args;
#[cfg(feature = "mpi")]
mod cluster;
mod cmd;
mod flight;
mod inputs;
mod keep;
mod manifest;
mod memory;
mod out_pair;
mod output;
mod plot;
mod progress;
mod scene_edit;
mod serve;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// See the Gödel universe from inside: a general-relativistic ray tracer.
#[derive(Parser, Debug)]
#[command(
    name = "godel",
    version,
    about,
    after_help = "Output (-o): a FOLDER for render and merge (they write NAME.png and NAME.exr \
there; a path ending in .png or .exr is refused), a FILE for shade and plot (the extension \
picks the format). Sequences name their folder in the script."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The subcommands, one module each, in the order of a user's work.
#[derive(Subcommand, Debug)]
enum Command {
    /// Trace a scene: writes FOLDER/<name>.png (preview) and FOLDER/<name>.exr (per-pixel data).
    Render(cmd::render::RenderArgs),
    /// Any camera of any observer at the event of a full-sphere data file, without tracing:
    /// turn, zoom, change projection, boost (aberration and Doppler shift).
    Look(cmd::look::LookArgs),
    /// Re-colour a data file without tracing again: texture, frequency, time and light shaders.
    Shade(cmd::shade::ShadeArgs),
    /// Image sequences with keyframed shader settings: numbered PNGs, and an MP4 with ffmpeg.
    Sequence(cmd::sequence::SequenceArgs),
    /// Serve a live web viewer of a data file, shaded on the GPU: shader controls, zoom, pixel
    /// records, saving; a full-sphere file can be looked around and boosted.
    View(cmd::view::ViewArgs),
    /// The live viewer of a scene whose observer can be moved and flown: where the browser's
    /// WebGL2 runs the GPU kernel the page traces every frame itself; otherwise each change
    /// of event is traced on the server, a coarse frame first, then the full one.
    Explore(cmd::explore::ExploreArgs),
    /// Join the part files of `render --part i/N` into the files a single run writes.
    Merge(cmd::merge::MergeArgs),
    /// Trace one geodesic (light ray or massive particle) and print it as CSV or JSON.
    Geodesic(cmd::geodesic::GeodesicArgs),
    /// Every light ray from a source at rest to an event, with emission times.
    Connect(cmd::connect::ConnectArgs),
    /// Draw figures (SVG or PNG).
    Plot(cmd::plot::PlotArgs),
}

fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Render(args) => cmd::render::run(args),
        Command::Look(args) => cmd::look::run(args),
        Command::Shade(args) => cmd::shade::run(args),
        Command::Sequence(args) => cmd::sequence::run(args),
        Command::View(args) => cmd::view::run(args),
        Command::Explore(args) => cmd::explore::run(args),
        Command::Merge(args) => cmd::merge::run(args),
        Command::Geodesic(args) => cmd::geodesic::run(args),
        Command::Connect(args) => cmd::connect::run(args),
        Command::Plot(args) => cmd::plot::run(args),
    }
}

/// Starts a thread that, on SIGINT, SIGTERM or SIGHUP, removes this process's temporary
/// files and exits with 128 + the signal (the shell's convention for a signalled process).
fn exit_on_signals() -> std::io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                // A child writing a temporary file stops first, so it cannot recreate it.
                let _encoder = cmd::sequence::stop_encoder();
                let removed = datafile::atomic::remove_live_temporaries();
                if removed > 0 {
                    eprintln!("godel: interrupted; removed {removed} temporary file(s)");
                }
                datafile::folders::remove_created_folders_left_empty();
                std::process::exit(128 + signal);
            }
        })?;
    Ok(())
}

/// The error and its causes on one line, each said once: a cause whose text the line
/// already holds (errors that quote their source) is left out.
fn message(err: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // Help and version go to stdout with code 0; usage errors to stderr with code 2.
            let _ = e.print();
            return ExitCode::from(e.exit_code().clamp(0, 255) as u8);
        }
    };
    if !matches!(cli.command, Command::View(_) | Command::Explore(_)) {
        if let Err(e) = exit_on_signals() {
            eprintln!("error: cannot watch for signals: {e}");
            return ExitCode::FAILURE;
        }
    }
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            // A failed run writes nothing: not even the folders it made for its output.
            datafile::folders::remove_created_folders_left_empty();
            // A reader that stops early (`godel … | head`) is no failure: end quietly, as
            // other Unix tools do.
            if err.chain().any(|c| {
                c.downcast_ref::<std::io::Error>()
                    .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
            }) {
                return ExitCode::SUCCESS;
            }
            eprintln!("error: {}", message(&err));
            // Bad input (flags, scene files) exits 2, other failures 1.
            if err
                .chain()
                .any(|c| c.is::<args::UsageError>() || c.is::<scene::SceneError>())
            {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}
