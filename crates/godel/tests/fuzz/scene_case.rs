//! One scene case in process: read the text (`Scene::from_str`); a refusal must be one
//! located line; an accepted scene is made tiny where the text asks for more (a mutated
//! example scene), traced (`render::driver::render`), and its records checked against the
//! data file's promises, round-tripped through the EXR codec, previewed, and shaded with the
//! data file's default settings in every layer.

use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;
use render::driver::NoProgress;
use scene::{Camera, Scene, SceneError, Shape};
use shade::{ShadeSettings, ShaderKind, Shading};

use crate::cli::Expect;

/// The name scene texts are read under in process.
pub const FILE: &str = "fuzz.toml";

/// Largest image side traced, and loops of a light ray followed (Gödel), in process.
const TINY_WIDTH: u32 = 8;
const TINY_HEIGHT: u32 = 4;
const TINY_LOOPS: f64 = 30.0;
const TINY_MAX_PAST_FLAT: f64 = 1000.0;
const TINY_STEPS: u64 = 100_000;

/// Checks a refused scene's message: one line, naming the file, located inside the text.
pub fn check_scene_error(e: &SceneError, text: &str) -> Result<(), String> {
    let shown = e.to_string();
    if shown.contains('\n') || shown.contains('\r') {
        return Err(format!("scene error is not one line: {shown:?}"));
    }
    if !shown.starts_with(FILE) {
        return Err(format!("scene error does not name the file: {shown:?}"));
    }
    if let Some(l) = e.location {
        let lines = text.split('\n').count();
        if l.line < 1 || l.line > lines || l.column < 1 {
            return Err(format!(
                "scene error at {l:?}, outside the text of {lines} lines: {shown:?}"
            ));
        }
    }
    Ok(())
}

/// Shrinks what makes a valid scene expensive, keeping its kind; returns what changed.
pub fn tiny(scene: &mut Scene) -> Vec<String> {
    let mut notes = Vec::new();
    let c = &mut scene.camera;
    let before = c.describe();
    match c {
        Camera::Pinhole { width, height, .. }
        | Camera::Panorama { width, height, .. }
        | Camera::Sphere { width, height } => {
            *width = (*width).min(TINY_WIDTH);
            *height = (*height).min(TINY_HEIGHT);
        }
        Camera::Fisheye { size, .. } => *size = (*size).min(TINY_WIDTH - 2),
    }
    if c.describe() != before {
        notes.push(format!("camera {before} -> {}", c.describe()));
    }
    // Samples multiply the rays: at most 2×2 (still more than one, to keep them tested).
    if scene.samples > 4 {
        notes.push(format!("samples {} -> 4", scene.samples));
        scene.samples = 4;
    }
    let most = match scene.metric.godel_a() {
        Some(a) => TINY_LOOPS * spacetime::Godel::new(a).shortest_loop_time(),
        None => TINY_MAX_PAST_FLAT,
    };
    if scene.trace.max_past > most {
        notes.push(format!("max_past {} -> {most}", scene.trace.max_past));
        scene.trace.max_past = most;
    }
    if scene.trace.max_steps > TINY_STEPS {
        notes.push(format!(
            "max_steps {} -> {TINY_STEPS}",
            scene.trace.max_steps
        ));
        scene.trace.max_steps = TINY_STEPS;
    }
    notes
}

/// What became of a scene text, and what the command line must do with it.
pub struct Verdict {
    pub outcome: String,
    pub expect: Expect,
    /// The scene's name and data file, when traced at its own size (not made tiny).
    pub exr: Option<(String, Vec<u8>)>,
    /// Whether the scene is cheap enough for the command line at its own size.
    pub cheap: bool,
}

/// Reads, traces and checks one scene text.
pub fn run(text: &str) -> Result<Verdict, String> {
    let mut scene = match Scene::from_str(text, FILE) {
        Ok(s) => s,
        Err(e) => {
            check_scene_error(&e, text)?;
            return Ok(Verdict {
                outcome: "refused".into(),
                expect: Expect::Code(2),
                exr: None,
                cheap: true,
            });
        }
    };
    let notes = tiny(&mut scene);
    let shrunk = !notes.is_empty();
    // A failure says how the scene was made tiny, so that it can be replayed as traced.
    let noted = |e: String| match shrunk {
        true => format!("{e}\n(traced made tiny: {})", notes.join("; ")),
        false => e,
    };
    let (data, _stats) = match render::driver::render(&scene, &NoProgress) {
        Ok(r) => r,
        Err(e) => {
            crate::shading_case::one_line("render", &e)?;
            return Ok(Verdict {
                outcome: "refused by the tracer".into(),
                expect: Expect::Failure,
                exr: None,
                cheap: !shrunk,
            });
        }
    };
    check_records(&scene, &data).map_err(noted)?;
    let bytes = round_trip(&data).map_err(noted)?;
    shade_all(&scene, &data).map_err(noted)?;
    let hits = data.records.iter().filter(|r| r.is_hit()).count();
    Ok(Verdict {
        outcome: format!(
            "traced{}, {}",
            if shrunk { " (made tiny)" } else { "" },
            if hits > 0 { "some hit" } else { "none hit" }
        ),
        expect: Expect::Files(vec![
            format!("{}.exr", scene.name),
            format!("{}.png", scene.name),
        ]),
        exr: (!shrunk).then(|| (scene.name.clone(), bytes)),
        cheap: !shrunk,
    })
}

/// The data file's promises about records (docs/guide/src/data-file.md).
pub fn check_records(scene: &Scene, data: &DataFile) -> Result<(), String> {
    // One record per sample: the camera's size times the samples per side.
    let s = scene.supersample() as usize;
    let (w, h) = (
        scene.camera.width() as usize * s,
        scene.camera.height() as usize * s,
    );
    if (data.width, data.height, data.records.len()) != (w, h, w * h) {
        return Err(format!(
            "data file {}×{} with {} records for a {w}×{h} sample grid",
            data.width,
            data.height,
            data.records.len()
        ));
    }
    let objects = scene.objects.len() as i32;
    let t_obs = scene.observer.event.t;
    // t_emit is stored in f32 and computed as a difference of times near t_obs.
    let slack = 1e-4 * (1.0 + scene.trace.max_past) + 1e-12 * t_obs.abs();
    for (i, r) in data.records.iter().enumerate() {
        let at = format!("pixel ({}, {})", i % w, i / w);
        // The camera ray's direction: a unit vector for every traced ray, zero otherwise.
        let view = r.view.map(f64::from);
        let norm = (view[0] * view[0] + view[1] * view[1] + view[2] * view[2]).sqrt();
        let traced = r.status != RayStatus::NotTraced;
        if (traced && (norm - 1.0).abs() > 1e-5) || (!traced && norm != 0.0) {
            return Err(format!(
                "{at}: camera ray direction {view:?} for status {:?}",
                r.status
            ));
        }
        if r.status != RayStatus::Hit {
            let miss = PixelRecord {
                view: r.view,
                ..PixelRecord::miss(r.status)
            };
            if *r != miss {
                return Err(format!(
                    "{at}: status {:?} but the record is not a miss: {r:?}",
                    r.status
                ));
            }
            continue;
        }
        if !(0..objects).contains(&r.object) {
            return Err(format!("{at}: hit object {} of {objects}", r.object));
        }
        let fields = [
            r.u, r.v, r.g, r.t_emit, r.x, r.y, r.z, r.lambda, r.cos_i, r.dir[0], r.dir[1], r.dir[2],
        ];
        if fields.iter().any(|v| !v.is_finite()) {
            return Err(format!(
                "{at}: a hit with a value that is not finite: {r:?}"
            ));
        }
        if r.g <= 0.0 {
            return Err(format!("{at}: frequency shift g = {} ≤ 0: {r:?}", r.g));
        }
        // Beyond r = 2a the coordinate t is no time function (closed timelike curves), so
        // only for an observer on the axis (rays stay within r < 2a) or in flat spacetime
        // must light arrive from the past within max_past.
        let t = f64::from(r.t_emit);
        let on_axis = scene.observer.event.x == 0.0 && scene.observer.event.y == 0.0;
        let ordered = on_axis || scene.metric.godel_a().is_none();
        if ordered && (t > slack || t < -scene.trace.max_past - slack) {
            return Err(format!(
                "{at}: t_emit = {t} outside [−max_past, 0] = [{}, 0]: {r:?}",
                -scene.trace.max_past
            ));
        }
        if r.cos_i.abs() > 1.0 + 1e-5 {
            return Err(format!("{at}: cos_i = {} outside [−1, 1]", r.cos_i));
        }
        let n = r
            .dir
            .iter()
            .map(|c| f64::from(*c).powi(2))
            .sum::<f64>()
            .sqrt();
        if (n - 1.0).abs() > 1e-3 {
            return Err(format!("{at}: photon direction of length {n}: {r:?}"));
        }
        let sphere = !matches!(scene.objects[r.object as usize].shape, Shape::Plane { .. });
        if sphere && !((0.0..=1.0).contains(&r.u) && (0.0..=1.0).contains(&r.v)) {
            return Err(format!(
                "{at}: texture coordinates ({}, {}) outside [0, 1]",
                r.u, r.v
            ));
        }
    }
    if let Some(name) = inside(scene) {
        // Every ray starts inside that object and reaches its inner surface within max_past:
        // it hits (that surface, or an object before it), unless a bound ran out.
        for (i, r) in data.records.iter().enumerate() {
            if matches!(r.status, RayStatus::Escaped | RayStatus::Failed) {
                return Err(format!(
                    "pixel ({}, {}): status {:?}, but the observer is inside object {name:?}, whose inner surface every ray reaches within max_past",
                    i % w,
                    i / w,
                    r.status
                ));
            }
        }
    }
    if data.lights.len() != scene.lights.len() {
        return Err(format!(
            "{} light planes for {} lights",
            data.lights.len(),
            scene.lights.len()
        ));
    }
    for (k, plane) in data.lights.iter().enumerate() {
        // Irradiance is ≥ 0 (infinite at a caustic), NaN where a shadow search ran out.
        if let Some(v) = plane.iter().find(|v| **v < 0.0) {
            return Err(format!("light_{k} has a negative value {v}"));
        }
        for (i, v) in plane.iter().enumerate() {
            let r = &data.records[i];
            if !r.is_hit() && *v != 0.0 {
                return Err(format!("light_{k} = {v} at pixel {i}, which hit nothing"));
            }
        }
    }
    Ok(())
}

/// The data file survives encoding and decoding bit for bit; returns its encoding.
pub fn round_trip(data: &DataFile) -> Result<Vec<u8>, String> {
    let bytes = data
        .to_bytes()
        .map_err(|e| format!("cannot encode the data file: {e}"))?;
    let back =
        DataFile::from_bytes(&bytes).map_err(|e| format!("cannot read back the data file: {e}"))?;
    let bits = |d: &DataFile| -> Vec<u32> {
        d.records
            .iter()
            .flat_map(|r| {
                [
                    r.u, r.v, r.g, r.t_emit, r.x, r.y, r.z, r.lambda, r.cos_i, r.dir[0], r.dir[1],
                    r.dir[2], r.view[0], r.view[1], r.view[2],
                ]
                .map(f32::to_bits)
                .into_iter()
                .chain([r.object as u32, r.status.code()])
            })
            .chain(d.lights.iter().flatten().map(|v| v.to_bits()))
            .collect()
    };
    if back.header != data.header
        || bits(&back) != bits(data)
        || (back.width, back.height) != (data.width, data.height)
    {
        return Err("the data file does not read back as written".into());
    }
    Ok(bytes)
}

/// The preview, and the data file's defaults in every layer, are accepted and shade the
/// whole picture.
pub fn shade_all(scene: &Scene, data: &DataFile) -> Result<(), String> {
    let textures = shade::textures_for_scene(scene).map_err(|e| format!("textures: {e}"))?;
    let preview = shade::texture_shader::preview_with_textures(data, &textures, scene);
    // Pictures have the camera's size: the samples of each pixel are filtered into it.
    let size = (scene.camera.width(), scene.camera.height());
    if preview.dimensions() != size {
        return Err(format!("preview {:?} for {size:?}", preview.dimensions()));
    }
    let defaults = ShadeSettings::defaults_for(data);
    for kind in ShaderKind::ALL {
        if kind == ShaderKind::Light && data.lights.is_empty() {
            continue;
        }
        let settings = ShadeSettings {
            shaders: vec![kind],
            ..defaults.clone()
        };
        let shading = Shading::new(data, &settings).map_err(|e| {
            format!("the data file's default settings are refused for {kind:?}: {e}")
        })?;
        let img = shading.image(data);
        if img.dimensions() != size {
            return Err(format!(
                "{kind:?} image {:?} for {size:?}",
                img.dimensions()
            ));
        }
    }
    Ok(())
}

/// The name of an object the observer is certainly inside, with its inner surface in reach of
/// every ray within max_past: a local ball centred on the observer's position (at rest) or
/// falling freely from the observer's own event, or a coordinate sphere around the observer,
/// each small against a (≤ a/2), near the axis, and max_past long enough to cross it (a
/// ball moving at speed v is crossed within γ(1 + v)·2R of coordinate time; 4× that is asked).
fn inside(scene: &Scene) -> Option<String> {
    let a = scene.metric.godel_a().unwrap_or(f64::INFINITY);
    let o = scene.observer.event;
    let near_axis = o.x.hypot(o.y) <= 0.25 * a.min(1e300);
    if !near_axis {
        return None;
    }
    scene.objects.iter().find_map(|ob| {
        let (radius, gamma_1v) = match (ob.shape, ob.motion) {
            (Shape::Sphere { radius }, scene::Motion::Rest { position })
                if (position.x, position.y, position.z) == (o.x, o.y, o.z) =>
            {
                (radius, 1.0)
            }
            (Shape::Sphere { radius }, scene::Motion::Geodesic { start, velocity })
                if start == o =>
            {
                (radius, velocity.gamma() * (1.0 + velocity.speed))
            }
            (Shape::CoordinateSphere { center, radius }, _) => {
                let d = ((center[0] - o.x).powi(2)
                    + (center[1] - o.y).powi(2)
                    + (center[2] - o.z).powi(2))
                .sqrt();
                if d < 0.5 * radius && radius <= 0.25 * a {
                    (radius, 1.0)
                } else {
                    return None;
                }
            }
            _ => return None,
        };
        let reach = 4.0 * gamma_1v * 2.0 * radius;
        (radius <= 0.5 * a && radius > 1e-6 * a.min(1.0) && scene.trace.max_past >= reach)
            .then(|| ob.name.clone())
    })
}
