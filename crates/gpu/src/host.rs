//! The offscreen host of the kernel: compiles it in a [`Context`], uploads the scene table,
//! draws the sample grid in tiles, each tile in rounds (docs/physics.md, "The GPU kernel",
//! "Rounds": each round takes every sample of the tile on from its last checkpoint, so that no
//! draw runs long, no GPU watchdog fires and a cancelled run stops soon) into the layers of
//! float array textures, reads the slots back and turns them into the data file's records and
//! light planes. No physics here: the kernel does it.

use crate::context::Context;
use crate::input::{light_channel, KernelInput, Uniforms, PHASE_DONE, TABLE_WIDTH};
use crate::KERNEL;
use datafile::record::{PixelRecord, RayStatus};
use glow::HasContext;
use render::driver::Progress;
use std::time::Instant;

/// The fragment kernel's companion: one triangle that covers the viewport.
const VERTEX: &str = "#version 300 es
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
";

/// Largest side of one draw, in samples (the render targets' size).
pub const MAX_DRAW_SIDE: u32 = 256;
/// Smallest side of one draw.
const MIN_DRAW_SIDE: u32 = 16;
/// What one draw should take: long enough to keep the GPU busy, short enough for watchdogs,
/// progress and cancellation.
const DRAW_SECONDS: f64 = 0.1;
/// Passes per sample in a tile's first round (the kernel halves or doubles a sample's budget
/// from round to round as its work needs).
pub const FIRST_BUDGET: i32 = 2048;
/// Rounds per tile at most: a sample not finished after them is marked "work limit". Far
/// above what a sample needs (each round takes it at least to its next checkpoint, unless
/// llvmpipe's loop limit cuts the round).
pub const MAX_ROUNDS: u32 = 4096;

#[derive(Debug, thiserror::Error)]
pub enum HostError {
    #[error(transparent)]
    Context(#[from] crate::context::ContextError),
    #[error("the GPU kernel did not compile on {renderer}: {log}")]
    Compile { renderer: String, log: String },
    #[error("the GPU failed: {0}")]
    Gl(String),
    #[error(transparent)]
    Check(#[from] crate::check::CheckError),
    /// The scene is one the kernel does not trace ([`crate::input::refusal`]).
    #[error("{0}")]
    Unsupported(String),
}

/// The kernel compiled for one scene, ready to trace it.
pub struct GpuTracer {
    ctx: Context,
    program: glow::Program,
    table: glow::Texture,
    framebuffer: glow::Framebuffer,
    /// Two array textures of a tile's slots, one layer per slot: a round reads one and writes
    /// the other.
    layers: [glow::Texture; 2],
    buffers: usize,
    vao: glow::VertexArray,
    input: KernelInput,
}

/// How a trace cuts its work: the side of its tiles (None: each about DRAW_SECONDS), and the
/// passes per sample of a tile's first round. The records do not depend on it
/// (docs/physics.md, "Rounds").
#[derive(Clone, Copy, Debug)]
pub struct Tiling {
    pub side: Option<u32>,
    pub first_budget: i32,
}

impl Default for Tiling {
    fn default() -> Tiling {
        Tiling {
            side: None,
            first_budget: FIRST_BUDGET,
        }
    }
}

/// What a GPU trace produced: the sample grid's records and light planes.
pub struct Traced {
    pub records: Vec<PixelRecord>,
    pub lights: Vec<Vec<f32>>,
    /// Rounds drawn, all tiles together (docs/physics.md, "Rounds").
    pub rounds: u64,
}

/// A kernel's probes over the samples it traced ([`GpuTracer::count_probes`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct ProbeCount {
    pub probes: f64,
    pub samples: usize,
}

impl ProbeCount {
    /// Probes a traced sample, on average (0 where none was traced).
    pub fn per_sample(&self) -> f64 {
        self.probes / self.samples.max(1) as f64
    }
}

impl GpuTracer {
    /// Makes a context, compiles the kernel for `input`'s scene and uploads its table.
    pub fn new(input: KernelInput) -> Result<GpuTracer, HostError> {
        GpuTracer::with_kernel(input, KERNEL)
    }

    /// The same with another kernel source (tests hold mutated kernels to the CPU: each
    /// mutation must be caught).
    pub fn with_kernel(input: KernelInput, kernel: &str) -> Result<GpuTracer, HostError> {
        let ctx = Context::new()?;
        let gl = &ctx.gl;
        let buffers = input.draw_buffers(ctx.draw_buffers);
        // SAFETY (this block and the methods below): GL calls on the context current on
        // this thread, with objects created here and buffers sized for what GL writes.
        unsafe {
            let program = compile(&ctx, &fragment_source(&input, buffers, kernel))?;
            let table = float_texture(gl, TABLE_WIDTH, input.table_rows, &input.table)?;
            let framebuffer = gl.create_framebuffer().map_err(HostError::Gl)?;
            let plan = input.round_plan(buffers);
            let layers = [slot_layers(gl, plan.layers)?, slot_layers(gl, plan.layers)?];
            let vao = gl.create_vertex_array().map_err(HostError::Gl)?;
            let tracer = GpuTracer {
                program,
                table,
                framebuffer,
                layers,
                buffers,
                vao,
                input,
                ctx,
            };
            tracer.set_scene_uniforms();
            // One sample drawn now: drivers compile shaders for the hardware on first use
            // (llvmpipe: seconds), which belongs to setting up, not to tracing.
            tracer.draw(0, 0, 1, 1, &render::driver::NoProgress, &mut 0)?;
            Ok(tracer)
        }
    }

    /// The probes of `kernel` (the kernel's source, or a variant of it) on `input`'s scene,
    /// all traced samples together: its `COUNT_PROBES` build writes each sample's probes
    /// into the record's `view[0]` (benchmarks and tests).
    pub fn count_probes(input: KernelInput, kernel: &str) -> Result<ProbeCount, HostError> {
        let source = format!("#define COUNT_PROBES 1\n{kernel}");
        let traced = GpuTracer::with_kernel(input, &source)?.trace(&render::driver::NoProgress)?;
        let samples = traced
            .records
            .iter()
            .filter(|r| r.status != RayStatus::NotTraced);
        Ok(samples.fold(ProbeCount::default(), |c, r| ProbeCount {
            probes: c.probes + f64::from(r.view[0]),
            samples: c.samples + 1,
        }))
    }

    /// The GL renderer that traces (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
    pub fn renderer(&self) -> &str {
        &self.ctx.renderer
    }

    unsafe fn set_scene_uniforms(&self) {
        let gl = &self.ctx.gl;
        set_uniforms(gl, self.program, &self.input.uniforms);
        let loc = |name: &str| gl.get_uniform_location(self.program, name);
        gl.uniform_1_i32(loc("u_prev").as_ref(), 1);
    }

    /// Traces the whole sample grid, draw by draw, reporting progress in samples; stops
    /// between draws when `progress` is cancelled (the records not traced stay "not traced").
    pub fn trace(&self, progress: &dyn Progress) -> Result<Traced, HostError> {
        self.trace_with(progress, Tiling::default())
    }

    /// The same, the work cut as `tiling` says (the records do not depend on it).
    pub fn trace_with(&self, progress: &dyn Progress, tiling: Tiling) -> Result<Traced, HostError> {
        let [w, h] = self.input.uniforms.size.map(|v| v as u32);
        // SAFETY: see `new`.
        unsafe {
            let gl = &self.ctx.gl;
            gl.use_program(Some(self.program));
            let budget = gl.get_uniform_location(self.program, "u_budget");
            gl.uniform_1_i32(budget.as_ref(), tiling.first_budget);
        }
        let n = self.input.light_count;
        let mut records = vec![PixelRecord::miss(RayStatus::NotTraced); (w * h) as usize];
        let mut lights = vec![vec![0.0f32; (w * h) as usize]; n];
        // Draws grow or shrink to take about DRAW_SECONDS each: strips of rows, each cut
        // into draws as wide as the current side.
        let mut side = tiling.side.unwrap_or(32).clamp(1, MAX_DRAW_SIDE);
        let mut rounds = 0;
        let mut row0 = 0u32;
        while row0 < h {
            let rows = side.min(h - row0);
            let mut col0 = 0u32;
            while col0 < w {
                if progress.cancelled() {
                    return Ok(Traced {
                        records,
                        lights,
                        rounds,
                    });
                }
                let cols = side.min(w - col0);
                let started = Instant::now();
                let Some(slots) = self.draw(col0, row0, cols, rows, progress, &mut rounds)? else {
                    return Ok(Traced {
                        records,
                        lights,
                        rounds,
                    });
                };
                self.collect(
                    &slots,
                    (col0, row0, cols, rows),
                    w,
                    &mut records,
                    &mut lights,
                );
                progress.advance(u64::from(cols * rows));
                col0 += cols;
                let took = started.elapsed().as_secs_f64().max(1e-6);
                let scale = (DRAW_SECONDS / took).sqrt().clamp(0.5, 2.0);
                if tiling.side.is_none() {
                    side = ((f64::from(side) * scale) as u32).clamp(MIN_DRAW_SIDE, MAX_DRAW_SIDE);
                }
            }
            row0 += rows;
        }
        Ok(Traced {
            records,
            lights,
            rounds,
        })
    }

    /// Traces one tile in rounds until each of its samples is finished (or MAX_ROUNDS), then
    /// makes its records and reads their slots back: per slot, cols × rows × 4 floats. None
    /// when `progress` is cancelled between rounds.
    fn draw(
        &self,
        col0: u32,
        row0: u32,
        cols: u32,
        rows: u32,
        progress: &dyn Progress,
        rounds: &mut u64,
    ) -> Result<Option<Vec<Vec<f32>>>, HostError> {
        let tile = (col0, row0, cols, rows);
        let slots = self.input.slots();
        let plan = self.input.round_plan(self.buffers);
        let mut from = 0;
        let mut phases = Vec::new();
        // SAFETY: see `new`.
        unsafe {
            for round in 0..MAX_ROUNDS {
                if progress.cancelled() {
                    return Ok(None);
                }
                self.pass(tile, round.min(1) as i32, 0, from, plan.rounds.clone())?;
                *rounds += 1;
                from = 1 - from;
                phases = self.read_layer(from, slots, cols, rows)?;
                if phases.chunks(4).all(|p| p[0] == PHASE_DONE) {
                    break;
                }
            }
            // The record's slots: the rounds' own, or a finishing draw's.
            if let Some(finish) = plan.finish {
                self.pass(tile, 1, 1, from, finish)?;
                from = 1 - from;
            }
            let mut read = (0..slots)
                .map(|s| self.read_layer(from, s, cols, rows))
                .collect::<Result<Vec<_>, _>>()?;
            // A sample still unfinished after MAX_ROUNDS is out of work.
            for (i, p) in phases.chunks(4).enumerate() {
                if p[0] != PHASE_DONE {
                    let code = RayStatus::WorkLimit as u32 as f32;
                    read[0][4 * i..4 * i + 4].copy_from_slice(&[-1.0, code, 0.0, 0.0]);
                }
            }
            Ok(Some(read))
        }
    }

    /// One round (`finish` 0) or the finishing draw (1) of a tile: reads the slots in array
    /// texture `from`, writes the layers `write` of the other, each draw into `buffers` layers
    /// from its first (the same render targets for every draw).
    unsafe fn pass(
        &self,
        (col0, row0, cols, rows): (u32, u32, u32, u32),
        round: i32,
        finish: i32,
        from: usize,
        write: std::ops::Range<usize>,
    ) -> Result<(), HostError> {
        let gl = &self.ctx.gl;
        gl.use_program(Some(self.program));
        gl.bind_vertex_array(Some(self.vao));
        gl.active_texture(glow::TEXTURE0);
        gl.bind_texture(glow::TEXTURE_2D, Some(self.table));
        gl.active_texture(glow::TEXTURE1);
        gl.bind_texture(glow::TEXTURE_2D_ARRAY, Some(self.layers[from]));
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.framebuffer));
        gl.viewport(0, 0, cols as i32, rows as i32);
        let loc = |name: &str| gl.get_uniform_location(self.program, name);
        gl.uniform_2_i32(loc("u_origin").as_ref(), col0 as i32, row0 as i32);
        gl.uniform_1_i32(loc("u_round").as_ref(), round);
        gl.uniform_1_i32(loc("u_finish").as_ref(), finish);
        let to = Some(self.layers[1 - from]);
        let attachments: Vec<u32> = (0..self.buffers)
            .map(|i| glow::COLOR_ATTACHMENT0 + i as u32)
            .collect();
        for first in write.step_by(self.buffers) {
            for (i, &attachment) in attachments.iter().enumerate() {
                let layer = (first + i) as i32;
                gl.framebuffer_texture_layer(glow::FRAMEBUFFER, attachment, to, 0, layer);
            }
            gl.draw_buffers(&attachments);
            if gl.check_framebuffer_status(glow::FRAMEBUFFER) != glow::FRAMEBUFFER_COMPLETE {
                return Err(HostError::Gl("float render targets are incomplete".into()));
            }
            gl.uniform_1_i32(loc("u_slot0").as_ref(), first as i32);
            gl.draw_arrays(glow::TRIANGLES, 0, 3);
        }
        gl_error(gl, "in a draw")
    }

    /// Layer `slot` of array texture `which` over the tile: cols × rows × 4 floats.
    unsafe fn read_layer(
        &self,
        which: usize,
        slot: usize,
        cols: u32,
        rows: u32,
    ) -> Result<Vec<f32>, HostError> {
        let gl = &self.ctx.gl;
        let texture = Some(self.layers[which]);
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.framebuffer));
        gl.framebuffer_texture_layer(
            glow::FRAMEBUFFER,
            glow::COLOR_ATTACHMENT0,
            texture,
            0,
            slot as i32,
        );
        gl.read_buffer(glow::COLOR_ATTACHMENT0);
        let mut data = vec![0.0f32; (cols * rows * 4) as usize];
        gl.read_pixels(
            0,
            0,
            cols as i32,
            rows as i32,
            glow::RGBA,
            glow::FLOAT,
            glow::PixelPackData::Slice(Some(f32_bytes_mut(&mut data))),
        );
        gl_error(gl, "reading a tile")?;
        Ok(data)
    }

    /// Turns a tile's slots into records and light values. Framebuffer row j is grid row
    /// row0 + j (the kernel counts rows from the framebuffer's first).
    fn collect(
        &self,
        slots: &[Vec<f32>],
        (col0, row0, cols, rows): (u32, u32, u32, u32),
        width: u32,
        records: &mut [PixelRecord],
        lights: &mut [Vec<f32>],
    ) {
        for j in 0..rows {
            for i in 0..cols {
                let at = ((j * cols + i) * 4) as usize;
                let slot = |s: usize| &slots[s][at..at + 4];
                let index = ((row0 + j) * width + col0 + i) as usize;
                let record = sample_record(|s| slot(s).try_into().expect("four channels"));
                records[index] = record;
                for (k, plane) in lights.iter_mut().enumerate() {
                    let (s, c) = light_channel(k);
                    plane[index] = light_value(record.status, slot(s)[c]);
                }
            }
        }
    }
}

/// The record of one sample from its slots (`slot(s)`: the four channels of slot s, as the
/// kernel writes them: the status in slot 0's second channel; the hit's values only for a hit,
/// the direction looked along for every traced ray).
pub fn sample_record(slot: impl Fn(usize) -> [f32; 4]) -> PixelRecord {
    let (s0, s1, s2, s3, s4) = (slot(0), slot(1), slot(2), slot(3), slot(4));
    let status = RayStatus::from_code(s0[1] as u32).unwrap_or(RayStatus::Failed);
    let view = [s2[3], s3[3], s4[0]];
    match status {
        RayStatus::Hit => PixelRecord {
            object: s0[0] as i32,
            status,
            u: s0[2],
            v: s0[3],
            g: s1[0],
            t_emit: s1[1],
            x: s2[0],
            y: s2[1],
            z: s2[2],
            lambda: s1[2],
            dir: [s3[0], s3[1], s3[2]],
            cos_i: s1[3],
            view,
            pol: [s4[1], s4[2], s4[3]],
        },
        RayStatus::NotTraced => PixelRecord::miss(status),
        _ => PixelRecord {
            view,
            ..PixelRecord::miss(status)
        },
    }
}

/// A light's value in the data file from its channel `v` in a sample of `status`: 0 where
/// nothing was hit; NaN, as the CPU writes, where the occlusion search ran out of work (the
/// kernel marks that by a negative value: irradiance is never negative).
pub fn light_value(status: RayStatus, v: f32) -> f32 {
    if status != RayStatus::Hit {
        0.0
    } else if v < 0.0 {
        f32::NAN
    } else {
        v
    }
}

impl Drop for GpuTracer {
    fn drop(&mut self) {
        let gl = &self.ctx.gl;
        // SAFETY: deleting objects this tracer created, on its context.
        unsafe {
            gl.delete_program(self.program);
            gl.delete_texture(self.table);
            for t in self.layers {
                gl.delete_texture(t);
            }
            gl.delete_framebuffer(self.framebuffer);
            gl.delete_vertex_array(self.vao);
        }
    }
}

/// The fragment shader's source as a host compiles it: `#version 300 es`, the scene's defines
/// ([`KernelInput::defines`] for `buffers` render targets), then `kernel` (the kernel's source,
/// with what an entry point adds).
pub fn fragment_source(input: &KernelInput, buffers: usize, kernel: &str) -> String {
    format!("#version 300 es\n{}{}", input.defines(buffers), kernel)
}

/// Compiles and links `fragment` with the full-viewport vertex shader on `ctx`.
///
/// # Safety
/// `ctx` must be current on this thread.
pub(crate) unsafe fn compile(ctx: &Context, fragment: &str) -> Result<glow::Program, HostError> {
    let gl = &ctx.gl;
    let compile_error = |log: String| HostError::Compile {
        renderer: ctx.renderer.clone(),
        log,
    };
    let program = gl.create_program().map_err(HostError::Gl)?;
    for (kind, source) in [
        (glow::VERTEX_SHADER, VERTEX),
        (glow::FRAGMENT_SHADER, fragment),
    ] {
        let shader = gl.create_shader(kind).map_err(HostError::Gl)?;
        gl.shader_source(shader, source);
        gl.compile_shader(shader);
        if !gl.get_shader_compile_status(shader) {
            return Err(compile_error(gl.get_shader_info_log(shader)));
        }
        gl.attach_shader(program, shader);
    }
    gl.link_program(program);
    if !gl.get_program_link_status(program) {
        return Err(compile_error(gl.get_program_info_log(program)));
    }
    Ok(program)
}

/// An RGBA32F texture of `width` × `rows` texels read with texelFetch (`data`: four floats a
/// texel, row by row), left bound to TEXTURE_2D.
///
/// # Safety
/// A context must be current on this thread, `gl` its functions.
pub(crate) unsafe fn float_texture(
    gl: &glow::Context,
    width: usize,
    rows: usize,
    data: &[f32],
) -> Result<glow::Texture, HostError> {
    assert_eq!(data.len(), width * rows * 4, "a texture's data fills it");
    let texture = gl.create_texture().map_err(HostError::Gl)?;
    gl.bind_texture(glow::TEXTURE_2D, Some(texture));
    for p in [glow::TEXTURE_MIN_FILTER, glow::TEXTURE_MAG_FILTER] {
        gl.tex_parameter_i32(glow::TEXTURE_2D, p, glow::NEAREST as i32);
    }
    gl.tex_image_2d(
        glow::TEXTURE_2D,
        0,
        glow::RGBA32F as i32,
        width as i32,
        rows as i32,
        0,
        glow::RGBA,
        glow::FLOAT,
        glow::PixelUnpackData::Slice(Some(f32_bytes(data))),
    );
    Ok(texture)
}

/// An RGBA32F array texture of `layers` layers of MAX_DRAW_SIDE² texels: a tile's slots.
///
/// # Safety
/// A context must be current on this thread, `gl` its functions.
unsafe fn slot_layers(gl: &glow::Context, layers: usize) -> Result<glow::Texture, HostError> {
    let texture = gl.create_texture().map_err(HostError::Gl)?;
    gl.bind_texture(glow::TEXTURE_2D_ARRAY, Some(texture));
    for p in [glow::TEXTURE_MIN_FILTER, glow::TEXTURE_MAG_FILTER] {
        gl.tex_parameter_i32(glow::TEXTURE_2D_ARRAY, p, glow::NEAREST as i32);
    }
    let side = MAX_DRAW_SIDE as i32;
    gl.tex_storage_3d(
        glow::TEXTURE_2D_ARRAY,
        1,
        glow::RGBA32F,
        side,
        side,
        layers as i32,
    );
    gl_error(gl, "making the render targets")?;
    Ok(texture)
}

/// The GL error, if any, as a [`HostError`] saying `when`.
///
/// # Safety
/// A context must be current on this thread, `gl` its functions.
pub(crate) unsafe fn gl_error(gl: &glow::Context, when: &str) -> Result<(), HostError> {
    match gl.get_error() {
        glow::NO_ERROR => Ok(()),
        err => Err(HostError::Gl(format!("GL error 0x{err:x} {when}"))),
    }
}

/// Sets the kernel's scene uniforms `u` (and the table's texture unit, 0) on `program`.
///
/// # Safety
/// A context must be current on this thread, `gl` its functions, `program` linked on it.
pub(crate) unsafe fn set_uniforms(gl: &glow::Context, program: glow::Program, u: &Uniforms) {
    gl.use_program(Some(program));
    let loc = |name: &str| gl.get_uniform_location(program, &format!("u_{name}"));
    gl.uniform_1_f32(loc("a").as_ref(), u.a);
    gl.uniform_2_f32_slice(loc("obs_t").as_ref(), &u.obs_t);
    gl.uniform_3_f32_slice(loc("obs_x").as_ref(), &u.obs_x);
    gl.uniform_matrix_4_f32_slice(loc("obs_static").as_ref(), false, &u.observer.obs_static);
    gl.uniform_4_f32_slice(loc("obs_to").as_ref(), &u.observer.obs_to);
    gl.uniform_4_f32_slice(loc("velocity").as_ref(), &u.velocity);
    gl.uniform_3_f32_slice(loc("forward").as_ref(), &u.forward);
    gl.uniform_3_f32_slice(loc("up").as_ref(), &u.up);
    gl.uniform_1_i32(loc("camera").as_ref(), u.camera);
    gl.uniform_2_f32_slice(loc("fov").as_ref(), &u.fov);
    gl.uniform_2_i32_slice(loc("size").as_ref(), &u.size);
    gl.uniform_1_f32(loc("max_past").as_ref(), u.max_past);
    gl.uniform_1_i32(loc("max_loops").as_ref(), u.max_loops);
    gl.uniform_1_i32(loc("lights").as_ref(), u.lights);
    gl.uniform_4_f32_slice(loc("member").as_ref(), &u.member);
    gl.uniform_1_i32(loc("table").as_ref(), 0);
    gl.uniform_1_i32(loc("two").as_ref(), 2);
}

fn f32_bytes(v: &[f32]) -> &[u8] {
    // SAFETY: f32 has no padding and any byte pattern of it is readable as u8.
    unsafe { std::slice::from_raw_parts(v.as_ptr().cast(), std::mem::size_of_val(v)) }
}

pub(crate) fn f32_bytes_mut(v: &mut [f32]) -> &mut [u8] {
    // SAFETY: as above; every byte pattern is a valid f32.
    unsafe { std::slice::from_raw_parts_mut(v.as_mut_ptr().cast(), std::mem::size_of_val(v)) }
}
