//! `godel look SPHERE.exr --camera KIND … -o VIEW.exr`: any camera of any observer at the
//! event of a full-sphere data file, without tracing (`look`; docs/physics.md,
//! "Observers at one event: aberration and Doppler"), read smoothly (bilinear within one
//! image of one object) or by nearest neighbour (`--filter`), with `--samples` per pixel. Writes `VIEW.exr` (the data file, whose embedded scene
//! is the sphere's with the camera and the observer's velocity and axes replaced) and
//! `VIEW.png` (the preview, shaded like `godel render`'s), both produced in memory and then
//! written together as `godel render` writes its pair (`output::write_data_and_preview`);
//! the output folder is checked before the sphere is read. Prints how far the source's
//! resolution limits the result.
//!
//! Exit 2 for bad flags (naming the flag) and for a data file that is not a static
//! observer's full sphere; exit 1 for unreadable or damaged files (their embedded scene
//! included), as `godel shade`.

use crate::args::{parse_vector, usage};
use crate::inputs::Inputs;
use crate::out_pair::OutPair;
use crate::output::{prepare, write_data_and_preview};
use anyhow::Context;
use clap::{Args, ValueEnum};
use datafile::DataFile;
use look::{look_with, resolution, Filter, LookError, LookView, Sampling, SphereSource};
use scene::{Camera, Scene};
use shade::hdr::PictureFormat;
use spacetime::LocalVelocity;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct LookArgs {
    /// The full-sphere data file: `godel render` of a scene with `[camera] kind = "sphere"`
    /// and an observer at rest.
    pub sphere: PathBuf,
    /// The camera (as `[camera] kind` in a scene).
    #[arg(long, value_enum)]
    pub camera: CameraKind,
    /// Camera forward direction X,Y,Z in the observer's own frame (default: the sphere's).
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub forward: Option<String>,
    /// Camera up direction X,Y,Z, orthogonal to forward (default: the sphere's).
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub up: Option<String>,
    /// Field of view in degrees: pinhole horizontal (required), fisheye circle (default 180).
    #[arg(long, allow_hyphen_values = true, value_name = "DEG")]
    pub fov: Option<f64>,
    /// Panorama horizontal field of view in degrees.
    #[arg(long, allow_hyphen_values = true, value_name = "DEG")]
    pub h_fov: Option<f64>,
    /// Panorama vertical field of view in degrees.
    #[arg(long, allow_hyphen_values = true, value_name = "DEG")]
    pub v_fov: Option<f64>,
    /// Image width in pixels.
    #[arg(long, allow_negative_numbers = true)]
    pub width: i64,
    /// Image height in pixels (default: the width for a fisheye, half of it for a sphere).
    #[arg(long, allow_negative_numbers = true)]
    pub height: Option<i64>,
    /// Observer velocity SPEED,DX,DY,DZ relative to the static observer, in its frame
    /// (|SPEED| < 1; a negative speed moves against the direction). Default: at rest.
    #[arg(long, allow_hyphen_values = true, value_name = "SPEED,DX,DY,DZ")]
    pub velocity: Option<String>,
    /// Samples per pixel, a square number (1, 4, 9, 16, … up to 256) on a grid in each pixel,
    /// kept in the data file as `godel render --samples` keeps its rays; the preview averages
    /// them (smooth edges).
    #[arg(
        long,
        default_value_t = 1,
        value_name = "N",
        allow_negative_numbers = true
    )]
    pub samples: i64,
    /// How the sphere is read: smooth (bilinear within one image of one object, nearest at
    /// the edges of objects and images) or nearest (every record a traced ray's, unchanged).
    #[arg(long, value_enum, default_value_t = FilterArg::Smooth)]
    pub filter: FilterArg,
    /// The data file to write (.exr); the preview goes beside it with the extension .png.
    #[arg(short, long, value_name = "VIEW.exr")]
    pub output: PathBuf,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FilterArg {
    Smooth,
    Nearest,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CameraKind {
    Pinhole,
    Panorama,
    Fisheye,
    Sphere,
}

/// The camera of the flags; a field of view given to a camera that has none is an error.
fn camera(args: &LookArgs) -> anyhow::Result<Camera> {
    let width = side("--width", args.width)?;
    let given_height = args.height.map(|h| side("--height", h)).transpose()?;
    let unused = |flag: &str, given: Option<f64>, what: &str| match given {
        Some(_) => Err(usage(flag, format!("not used by {what}"))),
        None => Ok(()),
    };
    let required = |flag: &str, given: Option<f64>, kind: &str| {
        given.ok_or_else(|| usage(flag, format!("required for a {kind} camera")))
    };
    let height = |default: Option<u32>, kind: &str| {
        given_height
            .or(default)
            .ok_or_else(|| usage("--height", format!("required for a {kind} camera")))
    };
    Ok(match args.camera {
        CameraKind::Pinhole => {
            unused("--h-fov", args.h_fov, "a pinhole camera (use --fov)")?;
            unused("--v-fov", args.v_fov, "a pinhole camera (use --fov)")?;
            Camera::Pinhole {
                fov_deg: required("--fov", args.fov, "pinhole")?,
                width,
                height: height(None, "pinhole")?,
            }
        }
        CameraKind::Panorama => {
            unused("--fov", args.fov, "a panorama (use --h-fov and --v-fov)")?;
            Camera::Panorama {
                h_fov_deg: required("--h-fov", args.h_fov, "panorama")?,
                v_fov_deg: required("--v-fov", args.v_fov, "panorama")?,
                width,
                height: height(None, "panorama")?,
            }
        }
        CameraKind::Fisheye => {
            unused("--h-fov", args.h_fov, "a fisheye (use --fov)")?;
            unused("--v-fov", args.v_fov, "a fisheye (use --fov)")?;
            let size = height(Some(width), "fisheye")?;
            if size != width {
                return Err(usage(
                    "--height",
                    format!("a fisheye image is square: must equal --width ({width}), got {size}"),
                ));
            }
            Camera::Fisheye {
                fov_deg: args.fov.unwrap_or(180.0),
                size,
            }
        }
        CameraKind::Sphere => {
            for (flag, given) in [
                ("--fov", args.fov),
                ("--h-fov", args.h_fov),
                ("--v-fov", args.v_fov),
            ] {
                unused(flag, given, "a sphere camera (always 360°×180°)")?;
            }
            Camera::Sphere {
                width,
                height: height(Some(width.div_ceil(2)), "sphere")?,
            }
        }
    })
}

/// An image side given with `flag`: a number of pixels, at least 1 (the camera's own checks
/// bound it above).
fn side(flag: &str, v: i64) -> anyhow::Result<u32> {
    if v < 1 {
        return Err(usage(flag, format!("must be at least 1 pixel, got {v}")));
    }
    u32::try_from(v).map_err(|_| usage(flag, format!("{v} pixels is far too many")))
}

/// `--velocity SPEED,DX,DY,DZ`.
fn velocity(text: &Option<String>) -> anyhow::Result<LocalVelocity> {
    let Some(text) = text else {
        return Ok(LocalVelocity::REST);
    };
    let [speed, dx, dy, dz] = parse_vector::<4>("--velocity", text)?;
    if speed.abs() >= 1.0 {
        return Err(usage(
            "--velocity",
            format!(
                "the speed must be below 1 (the speed of light), got {}",
                scene::short(speed)
            ),
        ));
    }
    if speed == 0.0 {
        return Ok(LocalVelocity::REST);
    }
    let sign = speed.signum();
    LocalVelocity::new(speed.abs(), [sign * dx, sign * dy, sign * dz]).ok_or_else(|| {
        usage(
            "--velocity",
            format!(
                "the direction must not be zero, got {},{},{}",
                scene::short(dx),
                scene::short(dy),
                scene::short(dz)
            ),
        )
    })
}

/// A sphere that cannot be looked at: a data file of the wrong kind (not a full sphere, a
/// moving observer's, anti-aliased) is a usage error (exit 2); a damaged one (its embedded
/// scene, its records) is a failure to read it (exit 1), as `godel shade` has it.
fn sphere_error(file: &str, e: LookError) -> anyhow::Error {
    match e {
        LookError::EmbeddedScene(_) | LookError::Data(_) | LookError::Inconsistent { .. } => {
            anyhow::anyhow!("{file}: {e}")
        }
        e => usage(file, e.to_string()),
    }
}

/// The flag that sets a view field named by `look`.
fn flag_of(field: &str, camera: CameraKind) -> &'static str {
    match field {
        "camera.fov_deg" => "--fov",
        "camera.h_fov_deg" => "--h-fov",
        "camera.v_fov_deg" => "--v-fov",
        "camera.width" => "--width",
        "camera.height" if camera == CameraKind::Fisheye => "--width",
        "camera.height" => "--height",
        "observer.forward" => "--forward",
        "observer.up" => "--up",
        "camera.samples" => "--samples",
        _ => "--velocity",
    }
}

pub fn run(args: LookArgs) -> anyhow::Result<()> {
    let started = Instant::now();
    let file = args.sphere.display().to_string();
    // As render's `-o x.exr` (any case), the preview beside it in the same case.
    let is_exr = PictureFormat::from_path(&args.output) == Some(PictureFormat::Exr);
    let png = match OutPair::parse("--output", &args.output, false)? {
        OutPair::Files { png, .. } if is_exr => png,
        _ => return Err(usage(
            "--output",
            format!(
                "must name the data file to write (.exr), got {}; the preview goes beside it as .png",
                args.output.display()
            ),
        )),
    };
    // Flags first, so that a typo is reported before any file is read.
    let camera = camera(&args)?;
    let velocity = velocity(&args.velocity)?;
    scene::samples_per_side(args.samples, camera.width(), camera.height())
        .map_err(|m| usage("--samples", m))?;
    let sampling = Sampling {
        filter: match args.filter {
            FilterArg::Smooth => Filter::Smooth,
            FilterArg::Nearest => Filter::Nearest,
        },
        samples: args.samples as u32,
    };
    let vector = |flag: &str, text: &Option<String>| {
        text.as_ref()
            .map(|t| parse_vector::<3>(flag, t))
            .transpose()
    };
    let (forward, up) = (
        vector("--forward", &args.forward)?,
        vector("--up", &args.up)?,
    );

    let names: Vec<String> = [&args.output, &png]
        .iter()
        .filter_map(|p| p.file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .collect();
    let dir = args
        .output
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(std::path::Path::new("."));
    prepare("--output", dir, &names)?;
    Inputs::new()
        .add("the sphere", &args.sphere)
        .refuse_outputs_over_inputs("--output", &[&args.output, &png])?;

    let sphere = DataFile::read(&args.sphere)?;
    let read = started.elapsed();
    let samples = u64::from(camera.width()) * u64::from(camera.height()) * args.samples as u64;
    crate::memory::check_writing(
        "--width",
        "a view of this width × height × samples",
        samples,
        sphere.lights.len(),
    )?;
    let source = SphereSource::of(&sphere).map_err(|e| sphere_error(&file, e))?;
    let view = LookView::new(
        camera,
        forward.unwrap_or(source.forward),
        up.unwrap_or(source.up),
        velocity,
    )
    .map_err(|e| match e {
        // The default up may not suit a given --forward: say where it came from.
        LookError::View { field, message } if field == "observer.up" && args.up.is_none() => {
            let up = source.up;
            usage(
                "--up",
                format!("{message}: the sphere's up {up:?} does not fit this --forward; give --up"),
            )
        }
        LookError::View { field, message } => usage(flag_of(field, args.camera), message),
        e => sphere_error(&file, e),
    })?;
    let data = look_with(&sphere, &view, sampling).map_err(|e| match e {
        LookError::View { field, message } => usage(flag_of(field, args.camera), message),
        e => sphere_error(&file, e),
    })?;
    let looked = started.elapsed();
    // A damaged file (exit 1), not a usage error: the message is kept, the scene error's
    // exit code is not.
    let scene = Scene::from_str(&data.header.scene_text, "scene embedded in the data file")
        .map_err(|e| anyhow::anyhow!("{file}: {e}"))
        .context(
            "the preview is shaded with the sphere's scene (textures resolve from the current folder)",
        )?;
    write_data_and_preview(&scene, &data, &args.output, &png, false)?;

    let r = resolution(&source, &view);
    let deg = |rad: f64| rad.to_degrees();
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    eprintln!(
        "{} from {} ({}×{} sphere): read {:.0} ms, look {:.0} ms, written in {:.0} ms",
        camera.describe(),
        file,
        source.width,
        source.height,
        ms(read),
        ms(looked - read),
        ms(started.elapsed() - looked)
    );
    eprintln!(
        "resolution: a source pixel spans {:.4}°; an output pixel {:.4}° to {:.4}° of the static observer's sky",
        deg(r.source_pixel),
        deg(r.output_pixel_min),
        deg(r.output_pixel_max)
    );
    if r.output_pixel_min > 0.0 && r.output_pixel_min < r.source_pixel {
        // (Less a rounding margin: a sphere of exactly the output's pixel size suffices.)
        let needed = (std::f64::consts::TAU / r.output_pixel_min - 1e-6).ceil() as u64;
        eprintln!(
            "  up to {:.1} output pixels share one source pixel: the sphere limits the detail; one source pixel per output pixel needs a sphere of {}×{}",
            r.source_pixel / r.output_pixel_min,
            needed,
            needed.div_ceil(2)
        );
    }
    Ok(())
}
