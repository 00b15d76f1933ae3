//! Progress on the terminal: the tracing bar, fed by the render driver's progress
//! consumer (the driver itself never learns about terminals).

use indicatif::{ProgressBar, ProgressStyle};
use render::driver::Progress;
use scene::Scene;

/// The progress bar, fed by the render driver.
pub struct Bar(pub ProgressBar);

impl Progress for Bar {
    fn advance(&self, pixels: u64) {
        self.0.inc(pixels);
    }
}

/// A progress bar over `pixels` pixels (hidden when `quiet`).
pub fn progress_bar(scene: &Scene, pixels: u64, quiet: bool) -> ProgressBar {
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(pixels)
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{prefix} [{bar:40}] {percent:>3}% {pos}/{len} px, {per_sec}, ETA {eta}",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    bar.set_prefix(format!("tracing {}", scene.name));
    bar
}
