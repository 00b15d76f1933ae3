//! Progress on the terminal: the tracing bar, fed by the render driver's progress
//! consumer (the driver itself never learns about terminals).

use indicatif::{ProgressBar, ProgressStyle};
use render::driver::Progress;
use scene::Scene;

/// The progress bar, fed by the render driver.
pub struct Bar(pub ProgressBar);

impl Progress for Bar {
    fn start(&self, pixels: u64) {
        self.0.set_length(pixels);
    }
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
            "{prefix} [{bar:40}] {percent:>3}% {pos}/{len} px, {rate}, ETA {eta}",
        )
        .expect("valid template")
        .with_key(
            "rate",
            |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = w.write_str(&rate_text(state.per_sec()));
            },
        )
        .progress_chars("=> "),
    );
    bar.set_prefix(format!("tracing {}", scene.name));
    bar
}

/// A rate as a whole number of pixels per second (`42013 px/s`; indicatif's own `{per_sec}`
/// prints `42,013.0142/s`).
pub fn rate_text(per_sec: f64) -> String {
    if per_sec.is_finite() && per_sec >= 0.0 {
        format!("{:.0} px/s", per_sec)
    } else {
        "– px/s".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_are_whole_numbers() {
        assert_eq!(rate_text(42_013.014_2), "42013 px/s");
        assert_eq!(rate_text(0.4), "0 px/s");
        assert_eq!(rate_text(f64::INFINITY), "– px/s");
        assert_eq!(rate_text(f64::NAN), "– px/s");
    }
}
