//! `godel render` under `mpirun` (cargo feature `mpi`; needs OpenMPI, which
//! scripts/test.sh installs when missing): 2 ranks write the very bytes of a
//! single-process run (a render, a 3-frame sequence, a fly-through keeping its data
//! files, and a stereo fly-through), a rank that fails ends the job non-zero with its rank named, and a rank killed
//! while tracing ends the job non-zero with nothing written.
#![cfg(feature = "mpi")]

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

// The integration binary's helpers; `pub` so that those this test leaves unused are not
// reported as dead (the integration binary uses them all).
#[path = "integration/common.rs"]
pub mod common;
use common::{files_in, stderr, write_scene, GODEL};

/// An `mpirun` with the flags a test machine needs (root in CI, fewer cores than ranks).
/// Its session folder lies in the test's own `dir`: OpenMPI makes it under TMPDIR, and two
/// jobs started at once under /tmp race to create the same `/tmp/ompi.HOST.UID` ("File
/// exists"), failing or hanging one of them.
fn mpirun_command(dir: &Path) -> Command {
    let session = dir.join("mpi-session");
    std::fs::create_dir_all(&session).unwrap();
    let mut command = Command::new("mpirun");
    command
        .args(["--allow-run-as-root", "--oversubscribe"])
        .env("TMPDIR", session);
    command
}

/// Runs `mpirun` (see `mpirun_command`) to its end.
fn mpirun(dir: &Path, args: &[&str]) -> Output {
    mpirun_command(dir)
        .args(args)
        .output()
        .expect("run mpirun (is OpenMPI installed? scripts/test.sh installs it)")
}

/// Runs `godel ARGS` on two ranks, with the environment variable `env` (`NAME=VALUE`) given
/// to both when asked.
fn on_two_ranks(dir: &Path, env: Option<&str>, args: &[&str]) -> Output {
    let mut all: Vec<&str> = match env {
        Some(v) => vec!["-x", v],
        None => vec![],
    };
    all.extend(["-n", "2", GODEL]);
    all.extend(args);
    mpirun(dir, &all)
}

/// The shared lit test scene, named "ranks".
fn scene_text(max_past: f64) -> String {
    common::lit_scene_text("ranks", max_past)
}

#[test]
fn two_ranks_write_the_bytes_of_one_process() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(tmp.path(), "ranks.toml", &scene_text(8.0));
    let single = tmp.path().join("single");
    let out = Command::new(GODEL)
        .args(["render", &scene, "-q", "-o", single.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));

    // With rank 0 working too (the default), and with rank 0 only serving the queue, so
    // that every tile surely travels from rank 1.
    for (root_works, dir) in [("1", "two"), ("0", "two-remote")] {
        let two = tmp.path().join(dir);
        let env = format!("GODEL_MPI_ROOT_WORKS={root_works}");
        let args = ["render", &scene, "-q", "-o", two.to_str().unwrap()];
        let out = on_two_ranks(tmp.path(), Some(&env), &args);
        let err = stderr(&out);
        assert!(out.status.success(), "{err}");
        assert!(err.contains("(2 ranks;"), "{err}");
        if root_works == "0" {
            assert!(err.contains("per rank: 0, "), "rank 0 traced: {err}");
        }
        for file in ["ranks.exr", "ranks.png"] {
            let a = std::fs::read(single.join(file)).unwrap();
            let b = std::fs::read(two.join(file)).unwrap();
            assert!(
                a == b,
                "{file} differs between 1 process and 2 ranks ({dir})"
            );
        }
    }
}

#[test]
fn a_rank_with_a_bad_scene_fails_the_job_and_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let good = write_scene(tmp.path(), "good.toml", &scene_text(8.0));
    let bad = write_scene(
        tmp.path(),
        "bad.toml",
        "name = \"ranks\"\n[camera]\nwidth = -3\n",
    );
    let dir = tmp.path().join("out");
    let o = dir.to_str().unwrap();
    // Rank 0 reads a good scene, rank 1 a bad one (as if its node saw another file).
    let out = mpirun(
        tmp.path(),
        &[
            "-n", "1", GODEL, "render", &good, "-q", "-o", o, ":", "-n", "1", GODEL, "render",
            &bad, "-q", "-o", o,
        ],
    );
    let err = stderr(&out);
    assert!(!out.status.success(), "the job succeeded: {err}");
    assert!(err.contains("godel: rank 1: "), "{err}");
    assert!(err.contains("bad.toml"), "{err}");
    assert!(!dir.join("ranks.exr").exists() && !dir.join("ranks.png").exists());
}

#[test]
fn a_rank_with_another_scene_fails_the_job_and_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let a = write_scene(tmp.path(), "a.toml", &scene_text(8.0));
    let b = write_scene(tmp.path(), "b.toml", &scene_text(7.0));
    let dir = tmp.path().join("out");
    let o = dir.to_str().unwrap();
    let out = mpirun(
        tmp.path(),
        &[
            "-n", "1", GODEL, "render", &a, "-q", "-o", o, ":", "-n", "1", GODEL, "render", &b,
            "-q", "-o", o,
        ],
    );
    let err = stderr(&out);
    assert!(!out.status.success(), "the job succeeded: {err}");
    assert!(err.contains("rank 1 read a different scene"), "{err}");
    assert!(!dir.join("ranks.exr").exists());
}

/// Runs the 3-frame sequence of the scene `scene` whose script after `[trace]` is `trace`
/// once in one process (into `one/`) and once on 2 ranks (into `two/`), rank 0 only serving
/// the queue so that every frame comes from rank 1; asserts both runs wrote the same file
/// names with the same bytes and returns the names.
fn sequence_alone_and_on_two_ranks(dir: &Path, scene: &str, trace: &str) -> Vec<String> {
    write_scene(dir, "fall.toml", scene);
    let script = |out: &str| {
        let text = format!(
            "output = \"{out}\"\nframes = 3\nmp4 = false\n[trace]\nscene = \"fall.toml\"\n{trace}"
        );
        write_scene(dir, &format!("{out}.toml"), &text)
    };
    let (one, two) = (script("one"), script("two"));
    let out = Command::new(GODEL)
        .args(["sequence", &one, "-q"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let out = on_two_ranks(
        dir,
        Some("GODEL_MPI_ROOT_WORKS=0"),
        &["sequence", &two, "-q"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let names = files_in(&dir.join("one"));
    assert_eq!(names, files_in(&dir.join("two")));
    for f in &names {
        let a = std::fs::read(dir.join("one").join(f)).unwrap();
        let b = std::fs::read(dir.join("two").join(f)).unwrap();
        if f == common::MANIFEST {
            // The manifest names the same files of the same sizes (their times differ).
            let files = |m: &[u8]| -> Vec<(String, String)> {
                let text = String::from_utf8_lossy(m).into_owned();
                let mut v: Vec<(String, String)> = text
                    .lines()
                    .map(|l| {
                        let p: Vec<&str> = l.splitn(3, ' ').collect();
                        (p[2].to_string(), p[0].to_string())
                    })
                    .collect();
                v.sort();
                v
            };
            assert_eq!(files(&a), files(&b), "the manifests differ");
            continue;
        }
        assert!(a == b, "{f} differs between 1 process and 2 ranks");
    }
    names
        .into_iter()
        .filter(|n| n != common::MANIFEST)
        .collect()
}

#[test]
fn two_ranks_write_the_frames_of_one_process() {
    let tmp = tempfile::tempdir().unwrap();
    // Observer time advancing, so each frame is traced.
    let names = sequence_alone_and_on_two_ranks(
        tmp.path(),
        &scene_text(6.0),
        "observer_time = [0.0, 1.5]\n",
    );
    assert_eq!(names.len(), 3, "{names:?}");
    // The frames differ from each other: the ball moved, so each frame was really made.
    let frame = |i: usize| std::fs::read(tmp.path().join(format!("one/frame_{i:04}.png"))).unwrap();
    assert!(frame(0) != frame(2));
}

#[test]
fn two_ranks_write_the_frames_and_data_files_of_one_process() {
    let tmp = tempfile::tempdir().unwrap();
    // A fly-through keeping each frame's data file: the observer moves and turns.
    let names = sequence_alone_and_on_two_ranks(
        tmp.path(),
        &scene_text(6.0),
        "keep_data = true\n[[keyframe]]\nframe = 0\n[[keyframe]]\nframe = 2\n\
         [keyframe.observer]\ntime = 1.0\nposition = { x = 0.3, y = 0.1, z = 0.0 }\n\
         forward = [0, 1, 0]\n",
    );
    assert_eq!(names.len(), 6, "{names:?}");
    let data = |i: usize| std::fs::read(tmp.path().join(format!("one/frame_{i:04}.exr"))).unwrap();
    assert!(
        data(0) != data(2),
        "the observer moved between frames 0 and 2"
    );
}

/// A stereo fly-through (issue 37) keeping both eyes' data files: each rank makes whole
/// frames, both eyes, so 2 ranks write the very files of one process.
#[test]
fn two_ranks_write_the_stereo_frames_of_one_process() {
    let tmp = tempfile::tempdir().unwrap();
    let stereo = scene_text(6.0).replace(
        "[camera]\n",
        "[camera]\nstereo = { separation = 0.2, layout = \"over-under\" }\n",
    );
    let names = sequence_alone_and_on_two_ranks(
        tmp.path(),
        &stereo,
        "keep_data = true\n[[keyframe]]\nframe = 0\n[[keyframe]]\nframe = 2\n\
         [keyframe.observer]\ntime = 1.0\nposition = { x = 0.3, y = 0.1, z = 0.0 }\n",
    );
    let expected: Vec<String> = (0..3)
        .flat_map(|i| ["left.exr", "png", "right.exr"].map(|ext| format!("frame_{i:04}.{ext}")))
        .collect();
    assert_eq!(names, expected);
}

/// Bound on every wait below; the job itself needs seconds.
const NEVER_HANGS: Duration = Duration::from_secs(180);

/// The process whose environment holds every one of `vars` (`NAME=value`), if any.
fn process_with(vars: &[&str]) -> Option<u32> {
    for entry in std::fs::read_dir("/proc").ok()?.flatten() {
        let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(env) = std::fs::read(entry.path().join("environ")) else {
            continue;
        };
        let entries: Vec<&[u8]> = env.split(|&b| b == 0).collect();
        if vars.iter().all(|v| entries.contains(&v.as_bytes())) {
            return Some(pid);
        }
    }
    None
}

/// Every process whose environment holds `var`, with its command line (diagnostics).
fn tagged(var: &str) -> Vec<(u32, String)> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(env) = std::fs::read(entry.path().join("environ")) else {
            continue;
        };
        if env.split(|&b| b == 0).any(|e| e == var.as_bytes()) {
            let cmd = std::fs::read(entry.path().join("cmdline")).unwrap_or_default();
            let env: Vec<String> = env
                .split(|&b| b == 0)
                .map(|e| String::from_utf8_lossy(e).into_owned())
                .filter(|e| e.starts_with("OMPI_COMM_WORLD"))
                .collect();
            found.push((pid, format!("{} {env:?}", String::from_utf8_lossy(&cmd))));
        }
    }
    found
}

/// CPU time (user + system) of process `pid` so far, in clock ticks.
fn cpu_ticks(pid: u32) -> Option<u64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // After the command name in parentheses: state is field 3, utime 14, stime 15.
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    Some(fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?)
}

/// Waits (bounded) until `f` gives a value.
fn wait_for<T>(what: &str, mut f: impl FnMut() -> Option<T>) -> T {
    let started = Instant::now();
    loop {
        if let Some(v) = f() {
            return v;
        }
        assert!(
            started.elapsed() < NEVER_HANGS,
            "gave up waiting for {what}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn a_rank_killed_while_tracing_fails_the_job_and_nothing_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    // Tens of seconds of tracing, all on rank 1 (rank 0 only serves the queue).
    let text = scene_text(30.0)
        .replace("width = 90", "width = 1600")
        .replace("height = 37", "height = 800");
    let scene = write_scene(tmp.path(), "slow.toml", &text);
    let out = tmp.path().join("out");
    // Marks this test's ranks among all processes of the machine.
    let tag = format!("GODEL_TEST_JOB={}", tmp.path().display());
    let mut job = mpirun_command(tmp.path())
        .args(["-x", &tag, "-x", "GODEL_MPI_ROOT_WORKS=0", "-n", "2", GODEL])
        .args(["render", &scene, "-q", "-o", out.to_str().unwrap()])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run mpirun (is OpenMPI installed? scripts/test.sh installs it)");
    let started = Instant::now();
    let rank1 = loop {
        if let Some(pid) = process_with(&[&tag, "OMPI_COMM_WORLD_RANK=1"]) {
            break pid;
        }
        if started.elapsed() > NEVER_HANGS || job.try_wait().unwrap().is_some() {
            let _ = job.kill();
            let status = job.wait().unwrap();
            let mut err = String::new();
            std::io::Read::read_to_string(&mut job.stderr.take().unwrap(), &mut err).unwrap();
            let ranks: Vec<(u32, String)> = tagged(&tag);
            panic!("rank 1 never seen; job {status}, tagged processes {ranks:?}, stderr: {err}");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    // Well into its work: a second of CPU time (100 ticks) is far past start-up.
    wait_for("rank 1 to trace", || cpu_ticks(rank1).filter(|&t| t >= 100));
    let killed = Command::new("kill")
        .args(["-KILL", &rank1.to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = wait_for("the job to end", || job.try_wait().unwrap());
    let mut err = String::new();
    std::io::Read::read_to_string(&mut job.stderr.take().unwrap(), &mut err).unwrap();
    assert!(!status.success(), "the job succeeded without rank 1: {err}");
    // No rank of the job is left running.
    assert!(process_with(&[&tag]).is_none(), "a rank outlived the job");
    // Nothing written: no image, no data file, no temporary (the folder itself was made
    // by the up-front check of the output).
    assert!(files_in(&out).is_empty(), "{:?}", files_in(&out));
}

/// Issue 10: the checks made before tracing hold under MPI too: rank 0 refuses an output
/// folder it cannot write, every rank a thread count beyond 8 per core.
#[test]
fn limits_are_checked_before_tracing_under_mpi() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(tmp.path(), "ranks.toml", &scene_text(8.0));
    let good = tmp.path().join("out");
    let cases: [(&str, &str, &str); 2] = [
        (
            "/dev/null/out",
            "1",
            "godel: rank 0: --output: cannot create the output folder",
        ),
        (good.to_str().unwrap(), "100000", ": --threads: at most "),
    ];
    for (out, threads, needle) in cases {
        let args = ["render", &scene, "-q", "-o", out, "--threads", threads];
        let o = on_two_ranks(tmp.path(), None, &args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(needle), "{err}");
        assert!(files_in(&good).is_empty());
    }
}
