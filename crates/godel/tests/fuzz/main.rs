//! Fuzzing (issue 10): random and mutated scenes, shade settings, sequence scripts and data
//! files, every case at tiny size on a worker thread under a per-case time limit. A case
//! that panics, breaks a promise checked here, or runs past the limit fails its test with
//! the case printed and a command that replays it alone.
//!
//! `GODEL_FUZZ_SEED` (default [`harness::DEFAULT_SEED`]) picks the cases,
//! `GODEL_FUZZ_CASES` (default [`harness::DEFAULT_CASES`]) how many over all tests,
//! `GODEL_FUZZ_CASE=K` replays case K alone (printing it), `GODEL_FUZZ_LIMIT_S` overrides
//! the limit ([`harness::DEFAULT_LIMIT`]). A sample of the cases also runs the `godel`
//! binary, with the command line's promises checked (`cli.rs`); sequences that re-shade a
//! data file in their own output folder, and outputs that are inputs, run it always
//! (`reshade_case.rs`).

// The integration binary's helpers; `pub` so that those the fuzz test leaves unused are not
// reported as dead (the integration binary uses them all).
#[path = "../integration/common.rs"]
pub mod common;

mod cli;
mod fixtures;
mod gen;
mod harness;
mod mutate;
mod reshade_case;
mod scene_case;
mod scenes;
mod shading_case;
mod shading_gen;

use harness::Fuzz;
use std::path::Path;

/// The example scenes shipped in `scenes/` (good and bad), as mutation bases.
fn example_scenes() -> Vec<String> {
    let root = testkit::scenes_dir();
    let mut out = Vec::new();
    for dir in [root.clone(), root.join("bad")] {
        let paths = testkit::toml_files(&dir);
        out.extend(paths.iter().map(|p| std::fs::read_to_string(p).unwrap()));
    }
    out
}

/// One in this many scene cases also runs `godel render` (when the scene is cheap at its
/// own size).
const CLI_EVERY_SCENE: u64 = 20;
/// One in this many settings, script and data-file cases also runs `godel shade` or
/// `godel sequence`.
const CLI_EVERY_SHADE: u64 = 15;

/// A scene text in process, and on a sample through `godel render`.
fn scene_case(fuzz: &mut Fuzz, k: u64, text: String, shown: &str) {
    let cli = fuzz.sampled(k, CLI_EVERY_SCENE);
    fuzz.run(k, shown, move || {
        let started = std::time::Instant::now();
        let v = scene_case::run(&text)?;
        // The command line is checked for its promises, not its speed: a scene that took
        // seconds in process (a far free-fall worldline, BENCHMARKS.md "Fuzzing") is not
        // traced a second time.
        let quick = started.elapsed() < std::time::Duration::from_secs(1);
        if cli && v.cheap && quick {
            let exr = v.exr.as_ref().map(|(n, b)| (n.as_str(), b.as_slice()));
            cli::render(&text, v.expect, exr)?;
            return Ok(format!("{} (and CLI)", v.outcome));
        }
        Ok(v.outcome)
    });
}

/// Random valid-looking scenes, traced at tiny size.
#[test]
fn fuzz_generated_scenes() {
    let mut fuzz = Fuzz::new("fuzz_generated_scenes", 0.35);
    for k in fuzz.indices() {
        let mut g = fuzz.gen(k);
        let text = scenes::scene(&mut g);
        let shown = text.clone();
        scene_case(&mut fuzz, k, text, &shown);
    }
    fuzz.finish();
}

/// The example scenes and generated ones, mutated: extremes, wrong types, unknown fields,
/// deleted and duplicated lines, truncation, flipped bytes.
#[test]
fn fuzz_mutated_scenes() {
    let examples = example_scenes();
    let mut fuzz = Fuzz::new("fuzz_mutated_scenes", 0.25);
    for k in fuzz.indices() {
        let mut g = fuzz.gen(k);
        let base = if g.chance(0.5) {
            g.pick(&examples)
        } else {
            scenes::scene(&mut g)
        };
        let (text, log) = mutate::text(&mut g, &base, &examples);
        let shown = format!("mutations: {}\n{text}", log.join("; "));
        scene_case(&mut fuzz, k, text, &shown);
    }
    fuzz.finish();
}

/// A text made by `make` for a fixture data file picked at random, mutated in 4 cases of 10:
/// the fixture's index, the text, and the case as shown on failure.
fn on_fixture(
    g: &mut gen::Gen,
    make: impl FnOnce(&mut gen::Gen, &fixtures::Fixture) -> String,
) -> (usize, String, String) {
    let fx = fixtures::get();
    let f = g.index(fx.data.len());
    let mut text = make(g, &fx.data[f]);
    let mut log = Vec::new();
    if g.chance(0.4) {
        (text, log) = mutate::text(g, &text, &[]);
    }
    let shown = format!("data file {f}; mutations: {}\n{text}", log.join("; "));
    (f, text, shown)
}

/// Settings files over the data files' defaults, generated and mutated; a sample through
/// `godel shade --settings`.
#[test]
fn fuzz_shade_settings() {
    let fx = fixtures::get();
    let mut fuzz = Fuzz::new("fuzz_shade_settings", 0.15);
    for k in fuzz.indices() {
        let (f, text, shown) = on_fixture(&mut fuzz.gen(k), |g, fixture| {
            let lights = fixture.data.lights.len();
            shading_gen::settings(g, &fixture.objects(), lights, &fx.images)
        });
        let cli = fuzz.sampled(k, CLI_EVERY_SHADE);
        fuzz.run(k, &shown, move || {
            let fixture = &fixtures::get().data[f];
            let outcome = shading_case::settings(&fixture.data, &text)?;
            if cli {
                let expect = match outcome.as_str() {
                    "shaded" => cli::Expect::Files(vec!["pic.png".into()]),
                    "refused" => cli::Expect::Code(2),
                    _ => cli::Expect::Failure,
                };
                cli::shade(&fixture.bytes, Some(&text), expect)?;
                return Ok(format!("{outcome} (and CLI)"));
            }
            Ok(outcome)
        });
    }
    fuzz.finish();
}

/// Sequence scripts on a data file, generated and mutated; a sample through
/// `godel sequence` (frames written all or none).
#[test]
fn fuzz_sequence_scripts() {
    let mut fuzz = Fuzz::new("fuzz_sequence_scripts", 0.1);
    for k in fuzz.indices() {
        let (f, text, shown) = on_fixture(&mut fuzz.gen(k), |g, fixture| {
            let lights = fixture.data.lights.len();
            shading_gen::script(g, "data.exr", &fixture.objects(), lights)
        });
        let cli = fuzz.sampled(k, CLI_EVERY_SHADE);
        fuzz.run(k, &shown, move || {
            let fixture = &fixtures::get().data[f];
            let path = fixtures::get().dir.join("script.toml");
            let outcome = shading_case::script(&fixture.data, &text, &path)?;
            // The command runs where the script reads data.exr beside it and writes a few
            // frames into frames/ beside it (or is refused before that).
            let dir = path.parent().unwrap_or(Path::new(""));
            let script = shade::Script::parse(&text, &path);
            let here = script.as_ref().is_ok_and(|s| {
                s.source == shade::FrameSource::Data(dir.join("data.exr"))
                    && s.output == dir.join("frames")
                    && s.frames <= 12
            });
            if cli && (here || script.is_err()) {
                let frames = script
                    .ok()
                    .filter(|_| outcome == "frames shaded")
                    .map(|s| s.frames);
                cli::sequence(&text, &fixture.bytes, frames)?;
                return Ok(format!("{outcome} (and CLI)"));
            }
            Ok(outcome)
        });
    }
    fuzz.finish();
}

/// Sequences that re-shade a data file lying in their own output folder among other files,
/// run twice (the second time with fewer frames), and outputs that are inputs (issue 24):
/// through the `godel` binary, every case.
#[test]
fn fuzz_sequences_beside_their_data() {
    let fx = fixtures::get();
    let mut fuzz = Fuzz::new("fuzz_sequences_beside_their_data", 0.01);
    for k in fuzz.indices() {
        let mut g = fuzz.gen(k);
        // Mostly scripts that run: the point is what a run does to the folder.
        let f = g.index(fx.data.len());
        let (objects, lights) = (fx.data[f].objects(), fx.data[f].data.lights.len());
        let mut text = shading_gen::script(&mut g, "data.exr", &objects, lights);
        let mut log = Vec::new();
        if g.chance(0.1) {
            (text, log) = mutate::text(&mut g, &text, &[]);
        }
        let shown = format!("data file {f}; mutations: {}\n{text}", log.join("; "));
        let over_inputs = g.chance(0.2);
        fuzz.run(k, &shown, move || {
            let bytes = &fixtures::get().data[f].bytes;
            if over_inputs {
                reshade_case::outputs_over_inputs(&text, bytes)
            } else {
                reshade_case::reshade(&mut g, &text, bytes)
            }
        });
    }
    fuzz.finish();
}

/// Data files: traced ones with bytes flipped, fields set to extremes, truncated or
/// extended, and with odd values in records and header; read and shaded in every layer,
/// a sample through `godel shade`.
#[test]
fn fuzz_data_files() {
    let fx = fixtures::get();
    let mut fuzz = Fuzz::new("fuzz_data_files", 0.15);
    for k in fuzz.indices() {
        let mut g = fuzz.gen(k);
        let f = g.index(fx.data.len());
        let (bytes, log) = if g.chance(0.6) {
            mutate::bytes(&mut g, &fx.data[f].bytes)
        } else {
            let mut data = fx.data[f].data.clone();
            let log = shading_case::odd_values(&mut g, &mut data);
            match data.to_bytes() {
                Ok(b) => (b, log),
                Err(e) => (Vec::new(), vec![format!("{log:?} not encodable: {e}")]),
            }
        };
        let settings = g.chance(0.3).then(|| {
            shading_gen::settings(
                &mut g,
                &fx.data[f].objects(),
                fx.data[f].data.lights.len(),
                &fx.images,
            )
        });
        let shown = format!(
            "data file {f}, {} bytes; changes: {}\nsettings: {settings:?}",
            bytes.len(),
            log.join("; ")
        );
        let cli = fuzz.sampled(k, CLI_EVERY_SHADE);
        fuzz.run(k, &shown, move || {
            let mut outcome = shading_case::data_bytes(&bytes)?;
            if let (Some(text), Ok(data)) = (&settings, datafile::DataFile::from_bytes(&bytes)) {
                outcome = format!(
                    "{outcome}; settings {}",
                    shading_case::settings(&data, text)?
                );
            }
            if cli {
                let expect = if outcome.starts_with("refused") {
                    cli::Expect::Code(1)
                } else {
                    cli::Expect::Failure
                };
                let expect = match shading_case::texture_layer_shades(&bytes) {
                    true => cli::Expect::Files(vec!["pic.png".into()]),
                    false => expect,
                };
                cli::shade(&bytes, None, expect)?;
                return Ok(format!("{outcome} (and CLI)"));
            }
            Ok(outcome)
        });
    }
    fuzz.finish();
}
