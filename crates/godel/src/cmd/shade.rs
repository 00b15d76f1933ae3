//! `godel shade DATA.exr --shader texture|frequency|time|light … -o out.png`: re-colours a
//! traced data file without tracing again (docs/guide/src/shading.md). The settings start
//! from the data file's defaults ([`shade::ShadeSettings::defaults_for`]), then a settings
//! file (`--settings`), then the convenience flags, in that order; a flag that no chosen
//! layer reads is refused ([`unused_flags`]). The picture's format follows the output's
//! extension (`.png` tone-mapped for display, `.exr` linear; [`shade::hdr`]); it is written
//! atomically, so a failed run leaves nothing at the output path.

use std::path::{Path, PathBuf};

use clap::Args;
use datafile::DataFile;
use shade::{
    BrightnessMode, ShadeError, ShadeSettings, ShaderKind, Shading, TextureChoice, TimeMode,
};

use crate::args::{parse_vector, usage};
use crate::inputs::Inputs;
use shade::hdr::{encode_exr, write_bytes, PictureFormat};

#[derive(Args, Debug)]
#[command(after_help = "\
Output: -o names the picture FILE (as for plot); its extension picks the format: .png \
(8-bit sRGB: exposure --ev, then the display tone curve, then overlays) or .exr (linear \
scene-referred RGB, 32-bit float channels R, G, B, no overlays, so --ev and --grid are \
refused there). Any other extension is an error.

Flags a chosen layer does not read are errors: --temperature, --exposure and --no-reference \
need the frequency layer; --window, --window-texture, --travel and --no-legend the time \
layer; --ambient and --light the light layer; --texture, --rotate and --offset a layer \
that paints textures (texture, time or light).

Limits: the data file a regular file of at most 8 GiB; the settings file a regular file of \
at most 16 MiB. A bad value names the flag that set it (or --settings).")]
pub struct ShadeArgs {
    /// The data file written by `godel render` (.exr).
    pub data: PathBuf,
    /// Output picture FILE: .png (for display) or .exr (linear HDR).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
    /// Shader layers, multiplied: texture, frequency, time, light; polarization draws ticks
    /// along the observed polarization over them (comma-separated or repeated, e.g.
    /// `frequency,time` or `texture,polarization`).
    #[arg(long, value_delimiter = ',', value_parser = parse_shader)]
    pub shader: Vec<ShaderKind>,
    /// A settings file (TOML; any subset of the settings fields).
    #[arg(long)]
    pub settings: Option<PathBuf>,
    /// Black-body temperature in K: `5000` for every object, or `NAME=5000` (repeatable).
    #[arg(long, allow_hyphen_values = true)]
    pub temperature: Vec<String>,
    /// Texture: `SPEC` for every object or `NAME=SPEC`; SPEC is scene, checker:ROWSxCOLS,
    /// gradient, uniform:R,G,B, image:PATH or earth (repeatable).
    #[arg(long)]
    pub texture: Vec<String>,
    /// Texture inside the time window, same forms as --texture.
    #[arg(long)]
    pub window_texture: Vec<String>,
    /// Time window T0,DT of emission time t_emit (relative to the observer): the time shader
    /// shows the window texture where T0 ≤ t_emit ≤ T0 + DT.
    #[arg(long, allow_hyphen_values = true)]
    pub window: Option<String>,
    /// False colour by light travel time over MIN,MAX (switches the time shader to it).
    #[arg(long, allow_hyphen_values = true)]
    pub travel: Option<String>,
    /// Physical brightness (radiance ratio Y(gT)/Y(T)) with this exposure.
    #[arg(long, allow_negative_numbers = true)]
    pub exposure: Option<f64>,
    /// PNG exposure compensation in stops (colours × 2^EV before the tone curve), -20 to 20.
    #[arg(long, allow_negative_numbers = true, value_name = "EV")]
    pub ev: Option<f64>,
    /// Orientation marks: azimuth/elevation grid with labelled ticks (PNG).
    #[arg(long)]
    pub grid: bool,
    /// Turn the body: `DEG` for every object or `NAME=DEG` (repeatable).
    #[arg(long, allow_hyphen_values = true)]
    pub rotate: Vec<String>,
    /// Move the texture: `U,V` for every object or `NAME=U,V` (repeatable).
    #[arg(long, allow_hyphen_values = true)]
    pub offset: Vec<String>,
    /// Ambient light of the light shader.
    #[arg(long, allow_negative_numbers = true)]
    pub ambient: Option<f64>,
    /// Light source K: `K=off`, `K=on` or `K=INTENSITY` (repeatable).
    #[arg(long)]
    pub light: Vec<String>,
    /// No reference squares (frequency shader).
    #[arg(long)]
    pub no_reference: bool,
    /// No legend (travel-time false colour).
    #[arg(long)]
    pub no_legend: bool,
    /// Of a stereo pair's data file (`NAME.left.exr`), shade this eye alone; without it a PNG
    /// holds both eyes (the partner file beside it) in the pair's layout.
    #[arg(long)]
    pub one_eye: bool,
}

/// The other eye of the stereo pair whose eye `data` (read from `path`) is, for a picture of
/// both (`shade::stereo::partner`); refused at `flag`, saying how to shade the one eye alone
/// when the other's file is not there.
pub(crate) fn stereo_partner(
    flag: &str,
    path: &Path,
    data: &DataFile,
) -> anyhow::Result<Option<shade::stereo::Partner>> {
    use shade::stereo::PartnerError;
    shade::stereo::partner(path, data).map_err(|e| match e {
        PartnerError::Read(e) => e.into(),
        e if e.is_missing() => usage(flag, format!("{e}; use --one-eye")),
        e => usage(flag, e.to_string()),
    })
}

fn parse_shader(s: &str) -> Result<ShaderKind, String> {
    s.parse()
}

/// Splits `NAME=VALUE` (or a bare `VALUE` meaning every object) and checks the name.
fn per_object<'a>(
    flag: &str,
    item: &'a str,
    names: &[String],
) -> anyhow::Result<(Vec<String>, &'a str)> {
    match item.split_once('=') {
        Some((name, value)) => {
            let name = name.trim();
            if !names.iter().any(|n| n == name) {
                return Err(usage(
                    flag,
                    format!(
                        "unknown object '{name}' (the data file's objects: {})",
                        names.join(", ")
                    ),
                ));
            }
            Ok((vec![name.to_string()], value))
        }
        None => Ok((names.to_vec(), item)),
    }
}

/// Applies the convenience flags to `s`.
fn apply_flags(args: &ShadeArgs, names: &[String], s: &mut ShadeSettings) -> anyhow::Result<()> {
    if !args.shader.is_empty() {
        s.shaders = args.shader.clone();
    }
    for item in &args.temperature {
        let (targets, v) = per_object("--temperature", item, names)?;
        let t: f64 = v
            .trim()
            .parse()
            .map_err(|_| usage("--temperature", format!("'{v}' is not a number")))?;
        crate::args::positive("--temperature", t)?;
        for n in targets {
            if let Some(o) = s.objects.get_mut(&n) {
                o.temperature = t;
            }
        }
    }
    for (flag, items, second) in [
        ("--texture", &args.texture, false),
        ("--window-texture", &args.window_texture, true),
    ] {
        for item in items {
            let (targets, v) = per_object(flag, item, names)?;
            let choice: TextureChoice = v.parse().map_err(|e: String| usage(flag, e))?;
            for n in targets {
                if let Some(o) = s.objects.get_mut(&n) {
                    if second {
                        o.window_texture = choice.clone();
                    } else {
                        o.texture = choice.clone();
                    }
                }
            }
        }
    }
    for item in &args.rotate {
        let (targets, v) = per_object("--rotate", item, names)?;
        let [deg] = parse_vector::<1>("--rotate", v)?;
        for n in targets {
            if let Some(o) = s.objects.get_mut(&n) {
                o.rotation_deg = deg;
            }
        }
    }
    for item in &args.offset {
        let (targets, v) = per_object("--offset", item, names)?;
        let [u, w] = parse_vector::<2>("--offset", v)?;
        for n in targets {
            if let Some(o) = s.objects.get_mut(&n) {
                o.offset_u = u;
                o.offset_v = w;
            }
        }
    }
    if let Some(w) = &args.window {
        let [t0, dt] = parse_vector::<2>("--window", w)?;
        crate::args::positive("--window (DT)", dt)?;
        s.time.mode = TimeMode::Window;
        s.time.t0 = t0;
        s.time.dt = dt;
    }
    if let Some(r) = &args.travel {
        let [lo, hi] = parse_vector::<2>("--travel", r)?;
        if hi <= lo {
            return Err(usage("--travel", format!("MAX must exceed MIN, got {r}")));
        }
        s.time.mode = TimeMode::Travel;
        s.time.travel_min = lo;
        s.time.travel_max = hi;
    }
    if let Some(e) = args.exposure {
        if !(e.is_finite() && e >= 0.0) {
            return Err(usage(
                "--exposure",
                format!("must be finite and ≥ 0, got {e}"),
            ));
        }
        s.brightness = BrightnessMode::Physical;
        s.exposure = e;
    }
    if let Some(a) = args.ambient {
        if !(a.is_finite() && a >= 0.0) {
            return Err(usage(
                "--ambient",
                format!("must be finite and ≥ 0, got {a}"),
            ));
        }
        s.light.ambient = a;
    }
    for item in &args.light {
        let (k, v) = item.split_once('=').ok_or_else(|| {
            usage(
                "--light",
                format!("expected K=on|off|INTENSITY, got '{item}'"),
            )
        })?;
        let k: usize = k
            .trim()
            .parse()
            .map_err(|_| usage("--light", format!("'{k}' is not a light index")))?;
        let n = s.light.sources.len();
        let source = s.light.sources.get_mut(k).ok_or_else(|| {
            usage(
                "--light",
                format!("light {k} does not exist (the data file has {n} light channel(s))"),
            )
        })?;
        match v.trim() {
            "on" => source.on = true,
            "off" => source.on = false,
            x => {
                let i: f64 = x
                    .parse()
                    .map_err(|_| usage("--light", format!("'{x}' is not on, off or a number")))?;
                if !(i.is_finite() && i >= 0.0) {
                    return Err(usage("--light", format!("intensity must be ≥ 0, got {x}")));
                }
                source.on = true;
                source.intensity = i;
            }
        }
    }
    if args.no_reference {
        s.reference_squares = false;
    }
    if args.no_legend {
        s.time.legend = false;
    }
    if let Some(ev) = args.ev {
        s.ev = ev;
    }
    if args.grid {
        s.grid = true;
    }
    Ok(())
}

/// The layer-specific flags given although no chosen layer reads them, and the display
/// flags given for a linear `.exr`: an error naming the first such flag and what it needs
/// (never silently ignored).
fn unused_flags(
    args: &ShadeArgs,
    shaders: &[ShaderKind],
    format: PictureFormat,
) -> anyhow::Result<()> {
    let has = |k: ShaderKind| shaders.contains(&k);
    let (freq, time, light) = (
        has(ShaderKind::Frequency),
        has(ShaderKind::Time),
        has(ShaderKind::Light),
    );
    // The polarization layer alone draws over the texture layer.
    let alone = shaders == [ShaderKind::Polarization];
    let paints = has(ShaderKind::Texture) || time || light || alone;
    let (f, t, l, p) = ("frequency", "time", "light", "texture, time or light");
    let checks = [
        ("--temperature", !args.temperature.is_empty(), freq, f),
        ("--exposure", args.exposure.is_some(), freq, f),
        ("--no-reference", args.no_reference, freq, f),
        ("--window", args.window.is_some(), time, t),
        ("--window-texture", !args.window_texture.is_empty(), time, t),
        ("--travel", args.travel.is_some(), time, t),
        ("--no-legend", args.no_legend, time, t),
        ("--ambient", args.ambient.is_some(), light, l),
        ("--light", !args.light.is_empty(), light, l),
        ("--texture", !args.texture.is_empty(), paints, p),
        ("--rotate", !args.rotate.is_empty(), paints, p),
        ("--offset", !args.offset.is_empty(), paints, p),
    ];
    for (flag, given, used, layer) in checks {
        if given && !used {
            let names: Vec<&str> = shaders.iter().map(|k| k.name()).collect();
            return Err(usage(
                flag,
                format!(
                    "has no effect with the shader layers {} (it needs the {layer} layer: add it with --shader)",
                    names.join(",")
                ),
            ));
        }
    }
    if format == PictureFormat::Exr {
        for (flag, given) in [("--ev", args.ev.is_some()), ("--grid", args.grid)] {
            if given {
                return Err(usage(
                    flag,
                    "has no effect on a linear .exr picture (no exposure, tone curve or overlays): write a .png",
                ));
            }
        }
    }
    Ok(())
}

/// The flag that set the settings field a [`ShadeError::Invalid`] names: the convenience
/// flag when it was given, else `--settings` when a settings file was, else the flag.
fn blamed_flag(args: &ShadeArgs, e: &ShadeError) -> &'static str {
    let ShadeError::Invalid { field, .. } = e else {
        return "--shader";
    };
    let parts: Vec<&str> = field.split(['.', '[']).collect();
    let (flag, given) = match parts.as_slice() {
        ["shaders", ..] => ("--shader", !args.shader.is_empty()),
        ["objects", _, "texture", ..] => ("--texture", !args.texture.is_empty()),
        ["objects", _, "window_texture", ..] => {
            ("--window-texture", !args.window_texture.is_empty())
        }
        ["objects", _, "temperature", ..] => ("--temperature", !args.temperature.is_empty()),
        ["objects", _, "rotation_deg", ..] => ("--rotate", !args.rotate.is_empty()),
        ["objects", _, "offset_u" | "offset_v", ..] => ("--offset", !args.offset.is_empty()),
        ["time", "t0" | "dt", ..] => ("--window", args.window.is_some()),
        ["time", "travel_min" | "travel_max", ..] => ("--travel", args.travel.is_some()),
        ["exposure", ..] => ("--exposure", args.exposure.is_some()),
        ["ev", ..] => ("--ev", args.ev.is_some()),
        ["light", "ambient", ..] => ("--ambient", args.ambient.is_some()),
        ["light", "sources", ..] => ("--light", !args.light.is_empty()),
        _ => ("--settings", args.settings.is_some()),
    };
    if !given && args.settings.is_some() {
        "--settings"
    } else {
        flag
    }
}

/// Settings errors are the user's input: exit code 2, like other usage errors.
pub fn settings_error(flag: &str, e: ShadeError) -> anyhow::Error {
    match e {
        ShadeError::Invalid { .. }
        | ShadeError::Settings { .. }
        | ShadeError::Script { .. }
        | ShadeError::NoLightChannels => usage(flag, e.to_string()),
        other => other.into(),
    }
}

pub fn run(args: ShadeArgs) -> anyhow::Result<()> {
    let format = PictureFormat::from_path(&args.output).ok_or_else(|| {
        usage(
            "--output",
            format!(
                "{}: unsupported picture type (use .png for display or .exr for linear HDR)",
                args.output.display()
            ),
        )
    })?;
    let mut inputs = Inputs::new();
    inputs.add("the data file", &args.data);
    if let Some(path) = &args.settings {
        inputs.add("the settings file", path);
    }
    inputs.refuse_outputs_over_inputs("--output", &[&args.output])?;
    let data = DataFile::read(&args.data)?;
    let partner = match (format, args.one_eye) {
        (PictureFormat::Png, false) => stereo_partner("DATA", &args.data, &data)?,
        _ => None,
    };
    if let Some(p) = &partner {
        inputs.add("the other eye's data file", &p.path);
        inputs.refuse_outputs_over_inputs("--output", &[&args.output])?;
    }
    let mut settings = ShadeSettings::defaults_for(&data);
    if let Some(path) = &args.settings {
        let text = scene::input::read_text(path, scene::input::MAX_TEXT_BYTES).map_err(|e| {
            usage(
                "--settings",
                format!("cannot read the settings file {}: {e}", path.display()),
            )
        })?;
        settings = settings
            .overlay_toml(&text, &path.display().to_string())
            .map_err(|e| settings_error("--settings", e))?;
    }
    apply_flags(&args, &data.header.object_names, &mut settings)?;
    unused_flags(&args, &settings.shaders, format)?;
    inputs
        .add_settings(&settings)
        .refuse_outputs_over_inputs("--output", &[&args.output])?;
    crate::output::prepare_file("--output", &args.output)?;
    let shading = Shading::new(&data, &settings).map_err(|e| {
        let flag = blamed_flag(&args, &e);
        settings_error(flag, e)
    })?;
    // The picture's size: an anti-aliased file holds s×s samples per pixel.
    let (w, h) = data.picture_size();
    let mut both = None;
    match format {
        PictureFormat::Png => match &partner {
            Some(p) => {
                let theirs = Shading::new(&p.data, &settings)
                    .map_err(|e| settings_error(blamed_flag(&args, &e), e))?
                    .image(&p.data);
                let ours = shading.image(&data);
                let (left, right) = p.left_right(&ours, &theirs);
                shade::write_png(&shade::stereo::compose(p.layout, left, right), &args.output)?;
                both = Some(p.layout.name());
            }
            None => shade::write_png(&shading.image(&data), &args.output)?,
        },
        PictureFormat::Exr => {
            let bytes = encode_exr(&shading.linear(&data), w, h, &args.output)?;
            write_bytes(&args.output, &bytes)?;
        }
    }
    let names: Vec<&str> = settings.shaders.iter().map(|k| k.name()).collect();
    let kind = match format {
        PictureFormat::Png => "",
        PictureFormat::Exr => ", linear RGB",
    };
    let eyes = both.map_or(String::new(), |l| format!(", both eyes {l}"));
    eprintln!(
        "wrote {} ({w}×{h}{kind}{eyes}, shader {})",
        args.output.display(),
        names.join(" × ")
    );
    if settings.shaders.contains(&ShaderKind::Time) && settings.time.mode == TimeMode::Travel {
        eprintln!(
            "travel time {}..{} (violet: shortest, yellow: longest)",
            settings.time.travel_min, settings.time.travel_max
        );
    }
    Ok(())
}
