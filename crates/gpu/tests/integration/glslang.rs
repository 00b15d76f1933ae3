//! Every kernel a host can build, compiled by an independent compiler: Khronos' reference
//! front end glslangValidator (Debian's glslang-tools; scripts/test.sh installs it) checks
//! each against the GLSL ES 3.00 specification (docs/physics.md, "The GPU kernel"). A driver's
//! compiler may accept what the specification refuses, or refuse what it accepts; this one is
//! the specification's.
//!
//! The sources are built as the hosts build them: `#version 300 es`, [`KernelInput::defines`]
//! of a scene input, then the entry point's source ([`gpu::host::fragment_source`]). The
//! pixel kernel, which calls every function, is compiled for every combination of what the
//! defines say: Gödel, Minkowski or a Gödel-type member (a causal one and one on the
//! sphere), with or without lights, every subset of the four object kinds, small arrays (the fewest objects, one light) or large ones (nine
//! objects, nine lights), and the render targets a host binds where 1, 4 or 8 can be bound.
//! The other entry points (COUNT_PROBES, RAY_PATH, each probe) share those functions and
//! differ only in `main`, which reads the metric and the render targets: they are compiled for
//! every metric and every number of render targets, each with the smallest scene and the
//! largest (the probes, which hosts build only for Gödel and Minkowski, for those).

use gpu::host::fragment_source;
use gpu::input::KernelInput;
use gpu::probe::Function;
use gpu::KERNEL;
use std::path::{Path, PathBuf};
use std::process::Command;

const VALIDATOR: &str = "glslangValidator";
/// Sources per run of the validator (it takes many; one process per source costs more than
/// the source).
const BATCH: usize = 40;

/// One source to check, and what it was made of (for the message when it fails).
struct Source {
    what: String,
    text: String,
}

/// The metrics of the sources: Minkowski's, Gödel's, and two Gödel-type members.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Minkowski,
    Godel,
    /// m² = 4Ω²: causal (the escape stop), m² > 0.
    Causal,
    /// m² = −Ω²: the sphere.
    Sphere,
}

/// The scene input every combination of `kind` starts from (its uniforms do not enter the
/// source).
fn base(kind: Kind) -> KernelInput {
    let name = match kind {
        Kind::Minkowski | Kind::Godel => "static-sphere",
        Kind::Causal | Kind::Sphere => "godel-type",
    };
    let path = testkit::scenes_dir().join(format!("{name}.toml"));
    let mut scene =
        scene::Scene::from_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    if let spacetime::Metric::GodelType(mut m) = scene.metric {
        m.m2 = if kind == Kind::Causal { 4.0 } else { -1.0 } * m.omega * m.omega;
        scene.metric = spacetime::Metric::GodelType(m);
    }
    KernelInput::new(&scene)
}

/// `base` as the input of a scene with the given metric, lights, object kinds (at rest, in free
/// fall, coordinate spheres, planes) and objects.
fn input(kind: Kind, lights: usize, kinds: [bool; 4], objects: usize) -> KernelInput {
    let mut input = base(kind);
    if kind == Kind::Minkowski {
        input.uniforms.metric = 0;
    }
    input.light_count = lights;
    input.uniforms.lights = lights as i32;
    input.kinds = kinds;
    input.objects = objects;
    input
}

/// The draw buffers hosts bind where 1, 4 or 8 can be.
const AVAILABLE: [usize; 3] = [1, 4, 8];

/// The kernel's entry points: what a host puts after the defines.
fn entry_points() -> Vec<(String, String)> {
    let mut out = vec![
        ("pixel kernel".to_string(), KERNEL.to_string()),
        // As the benchmark builds it (examples/bench.rs) and the page (hovered.js).
        (
            "COUNT_PROBES".to_string(),
            format!("#define COUNT_PROBES 1\n{KERNEL}"),
        ),
        (
            "RAY_PATH".to_string(),
            format!("#define RAY_PATH 1\n{KERNEL}"),
        ),
    ];
    out.extend(Function::ALL.map(|f| (f.define().to_string(), f.kernel())));
    out
}

/// Every source of the module documentation.
fn sources() -> Vec<Source> {
    let mut out = Vec::new();
    let mut add = |entry: &str, kernel: &str, input: &KernelInput| {
        for available in AVAILABLE {
            let buffers = input.draw_buffers(available);
            out.push(Source {
                what: format!(
                    "{entry}, {available} draw buffers available, defines:\n{}",
                    input.defines(buffers)
                ),
                text: fragment_source(input, buffers, kernel),
            });
        }
    };
    let entries = entry_points();
    let (pixel, others) = entries.split_first().expect("the pixel kernel");
    for kind in [Kind::Minkowski, Kind::Godel, Kind::Causal, Kind::Sphere] {
        let member = matches!(kind, Kind::Causal | Kind::Sphere);
        for lit in [false, true] {
            for bits in 0..16u8 {
                let kinds = [0, 1, 2, 3].map(|k| bits & (1 << k) != 0);
                let fewest = kinds.iter().filter(|k| **k).count();
                // Small arrays (the fewest objects, one light) and large ones (nine each).
                for large in [false, true] {
                    let objects = if large && fewest > 0 { 9 } else { fewest };
                    let lights = usize::from(lit) * if large { 9 } else { 1 };
                    let input = input(kind, lights, kinds, objects);
                    if !large || objects != fewest || lights > 1 {
                        add(&pixel.0, &pixel.1, &input);
                    }
                }
            }
        }
        for (name, kernel) in others {
            if member && !matches!(name.as_str(), "COUNT_PROBES" | "RAY_PATH") {
                continue;
            }
            add(name, kernel, &input(kind, 0, [false; 4], 0));
            add(name, kernel, &input(kind, 9, [true; 4], 9));
        }
    }
    out
}

/// A folder of this process's own for the sources, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("godel-glslang-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs the validator on `files`; its output where it refuses any (its exit status not 0).
fn validate(files: &[PathBuf]) -> Option<String> {
    let out = Command::new(VALIDATOR).args(files).output().unwrap_or_else(|e| {
        panic!(
            "{VALIDATOR} could not be run ({e}): install it (Debian: apt-get install glslang-tools; \
             scripts/test.sh does)"
        )
    });
    (!out.status.success()).then(|| {
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    })
}

/// The sources the validator refuses, each with its messages: written as `.frag` files (the
/// extension names the stage) and validated in batches, on as many threads as there are
/// cores; a refused batch is validated file by file to name the sources.
fn refused(sources: &[Source], scratch: &Path) -> Vec<String> {
    let files: Vec<PathBuf> = sources
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let path = scratch.join(format!("{i:05}.frag"));
            std::fs::write(&path, &s.text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            path
        })
        .collect();
    let indices: Vec<usize> = (0..files.len()).collect();
    let batches: Vec<&[usize]> = indices.chunks(BATCH).collect();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let next = std::sync::atomic::AtomicUsize::new(0);
    let failures = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| loop {
                let b = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(batch) = batches.get(b) else { break };
                let paths: Vec<PathBuf> = batch.iter().map(|&i| files[i].clone()).collect();
                if validate(&paths).is_none() {
                    continue;
                }
                for &i in *batch {
                    if let Some(log) = validate(std::slice::from_ref(&files[i])) {
                        let what = &sources[i].what;
                        let mut f = failures.lock().expect("no panic holding it");
                        f.push((i, format!("{what}\n{log}")));
                    }
                }
            });
        }
    });
    let mut failures = failures.into_inner().expect("no panic holding it");
    failures.sort();
    failures.into_iter().map(|(_, f)| f).collect()
}

#[test]
fn glslang_accepts_every_kernel_a_host_builds() {
    let sources = sources();
    let scratch = Scratch::new("all");
    let started = std::time::Instant::now();
    let failures = refused(&sources, &scratch.0);
    eprintln!(
        "{VALIDATOR}: {} sources in {:.1} s, {} refused",
        sources.len(),
        started.elapsed().as_secs_f64(),
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{VALIDATOR} refuses {} of {} kernels, the first:\n{}",
        failures.len(),
        sources.len(),
        failures[0]
    );
}

/// The check can fail: a source without one of its defines, and a probe entry point that
/// probe.glsl does not know, are refused, and named.
#[test]
fn glslang_refuses_a_broken_kernel() {
    let input = input(Kind::Godel, 1, [true, false, false, true], 2);
    let defines = input.defines(4);
    let godel = defines
        .lines()
        .find(|l| l.starts_with("#define GODEL "))
        .expect("a GODEL define");
    let broken = [
        Source {
            what: "no GODEL".into(),
            text: fragment_source(&input, 4, KERNEL).replacen(godel, "", 1),
        },
        Source {
            what: "an unknown probe".into(),
            text: fragment_source(&input, 4, &Function::Metric.kernel()).replacen(
                "#define PROBE PROBE_METRIC",
                "#define PROBE 99",
                1,
            ),
        },
        Source {
            what: "as built".into(),
            text: fragment_source(&input, 4, KERNEL),
        },
    ];
    let scratch = Scratch::new("broken");
    let failures = refused(&broken, &scratch.0);
    assert_eq!(failures.len(), 2, "{failures:?}");
    assert!(
        failures[0].starts_with("no GODEL") && failures[0].contains("GODEL"),
        "{}",
        failures[0]
    );
    assert!(
        failures[1].starts_with("an unknown probe") && failures[1].contains("unknown PROBE"),
        "{}",
        failures[1]
    );
}
