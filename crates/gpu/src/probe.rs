//! The kernel tested in pieces (docs/physics.md, "The GPU kernel"): a host for the kernel's
//! `PROBE` entry point (`src/probe.glsl`, appended after the kernel), which evaluates one
//! group of the kernel's functions per fragment on arguments the host uploads, so that each
//! can be held to its Rust twin (`tests/integration/probes.rs`). Compiled with the scene's defines, as
//! the pixel kernel is ([`crate::host::fragment_source`]).

use crate::context::Context;
use crate::host::{
    compile, f32_bytes_mut, float_texture, fragment_source, gl_error, set_uniforms, HostError,
};
use crate::input::{KernelInput, Uniforms};
use crate::KERNEL;
use glow::HasContext;

/// The probe entry point's source (appended after [`KERNEL`]).
pub const PROBE: &str = include_str!("probe.glsl");

/// Argument texels (four floats each) per evaluation, and result slots per evaluation.
pub const ARG_TEXELS: usize = 4;
pub const PROBE_SLOTS: usize = 8;
/// Evaluations per row of the draw (the args texture is ARG_TEXELS times as wide).
const PROBE_WIDTH: usize = 64;
/// Evaluations per call at most (rows of the draw: within every driver's texture size).
pub const MAX_EVALUATIONS: usize = PROBE_WIDTH * 256;

/// What one evaluation reads and writes.
pub type Args = [[f32; 4]; ARG_TEXELS];
pub type Results = [[f32; 4]; PROBE_SLOTS];

/// The groups of the kernel's functions a probe evaluates (each its `#if` in probe.glsl,
/// which says what goes in which argument and result).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function {
    /// atanA, atan2s, asinA, acosA, cis, sinA, cosA, atanA4, asinA4, asinh_, acosh_,
    /// atanh_, halfTanh.
    Elementary,
    /// metricAt, inverseMetricAt.
    Metric,
    /// christoffel, normalDisplacement.
    Christoffel,
    /// staticFrame, boostFrame.
    Frame,
    /// cameraDirection.
    Camera,
    /// toOrigin, applyPush, inverseIso.
    Isometry,
    /// originGeodesic, ogeoAt, returnParameter, flowRotation, timeDeviation.
    ClosedForm,
    /// transportLegs.
    Transport,
    /// shadowTheta, shadowG, shadowG4, areaDistanceSq, bigPhi.
    Shadow,
    /// ballMisses, planeMisses.
    Reject,
    /// lonLat.
    Surface,
    /// The Gödel-type family (FAMILY): typeOriginGeodesic, tgeoAt, typeReturnParameter,
    /// typeToOrigin, typeApplyPush, typeInverseIso.
    Family,
    /// The Gödel-type family (FAMILY): typeExactGeodesic, texAt.
    FamilyExact,
    /// The Gödel-type family's shadow rays (FAMILY): typeGodelRadius, typeShadowReach,
    /// typeShadowLambda, typeShadowLambda4, typeShadowExcess, typeShadowExcess4,
    /// typeShadowRay, typeShadowRayBack, typeAreaDistanceSq.
    FamilyShadow,
}

impl Function {
    pub const ALL: [Function; 14] = [
        Function::Elementary,
        Function::Metric,
        Function::Christoffel,
        Function::Frame,
        Function::Camera,
        Function::Isometry,
        Function::ClosedForm,
        Function::Transport,
        Function::Shadow,
        Function::Reject,
        Function::Surface,
        Function::Family,
        Function::FamilyExact,
        Function::FamilyShadow,
    ];

    /// Its name in probe.glsl.
    pub fn define(self) -> &'static str {
        match self {
            Function::Elementary => "PROBE_ELEMENTARY",
            Function::Metric => "PROBE_METRIC",
            Function::Christoffel => "PROBE_CHRISTOFFEL",
            Function::Frame => "PROBE_FRAME",
            Function::Camera => "PROBE_CAMERA",
            Function::Isometry => "PROBE_ISOMETRY",
            Function::ClosedForm => "PROBE_CLOSED_FORM",
            Function::Transport => "PROBE_TRANSPORT",
            Function::Shadow => "PROBE_SHADOW",
            Function::Reject => "PROBE_REJECT",
            Function::Surface => "PROBE_SURFACE",
            Function::Family => "PROBE_FAMILY",
            Function::FamilyExact => "PROBE_FAMILY_EXACT",
            Function::FamilyShadow => "PROBE_FAMILY_SHADOW",
        }
    }

    /// The source after the defines: this probe's entry point selected, the kernel, the probe.
    pub fn kernel(self) -> String {
        // The family's functions are compiled only where FAMILY is defined.
        let family = if matches!(
            self,
            Function::Family | Function::FamilyExact | Function::FamilyShadow
        ) {
            "#define FAMILY 1\n"
        } else {
            ""
        };
        format!("#define PROBE {}\n{family}{KERNEL}{PROBE}", self.define())
    }
}

/// The kernel compiled with one probe entry point, ready to evaluate it.
pub struct Prober {
    ctx: Context,
    program: glow::Program,
    framebuffer: glow::Framebuffer,
    targets: Vec<glow::Texture>,
    vao: glow::VertexArray,
}

impl Prober {
    /// Makes a context and compiles the kernel with `input`'s defines and `function`'s probe.
    pub fn new(input: &KernelInput, function: Function) -> Result<Prober, HostError> {
        let ctx = Context::new()?;
        // Every pass writes `buffers` slots from a multiple of `buffers`: the last pass stays
        // within the kernel's slots (at least 14) for any buffers ≤ 8 (ceil(8/b)·b ≤ 14).
        let buffers = ctx.draw_buffers.min(PROBE_SLOTS);
        let fragment = fragment_source(input, buffers, &function.kernel());
        // SAFETY (this block and the methods below): GL calls on the context current on
        // this thread, with objects created here and buffers sized for what GL writes.
        unsafe {
            let program = compile(&ctx, &fragment)?;
            let gl = &ctx.gl;
            let rows = MAX_EVALUATIONS / PROBE_WIDTH;
            let (framebuffer, targets) = render_targets(gl, buffers, PROBE_WIDTH, rows)?;
            let vao = gl.create_vertex_array().map_err(HostError::Gl)?;
            Ok(Prober {
                ctx,
                program,
                framebuffer,
                targets,
                vao,
            })
        }
    }

    /// Evaluates the probe once per element of `args` (at most [`MAX_EVALUATIONS`]) with the
    /// uniforms `uniforms`; the results in the same order.
    pub fn eval(&self, uniforms: &Uniforms, args: &[Args]) -> Result<Vec<Results>, HostError> {
        assert!(
            args.len() <= MAX_EVALUATIONS,
            "at most {MAX_EVALUATIONS} evaluations a call"
        );
        let gl = &self.ctx.gl;
        let rows = args.len().div_ceil(PROBE_WIDTH).max(1);
        let mut data = vec![0.0f32; PROBE_WIDTH * ARG_TEXELS * rows * 4];
        for (i, a) in args.iter().enumerate() {
            let at = i * ARG_TEXELS * 4;
            data[at..at + ARG_TEXELS * 4].copy_from_slice(a.as_flattened());
        }
        let mut results = vec![[[0.0f32; 4]; PROBE_SLOTS]; args.len()];
        let buffers = self.targets.len();
        // SAFETY: see `new`.
        unsafe {
            set_uniforms(gl, self.program, uniforms);
            // The table is unit 0 (never read by a probe); the arguments unit 1.
            gl.active_texture(glow::TEXTURE1);
            let texture = float_texture(gl, PROBE_WIDTH * ARG_TEXELS, rows, &data)?;
            let loc = gl.get_uniform_location(self.program, "u_args");
            gl.uniform_1_i32(loc.as_ref(), 1);
            gl.bind_vertex_array(Some(self.vao));
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.framebuffer));
            gl.viewport(0, 0, PROBE_WIDTH as i32, rows as i32);
            let slot0 = gl.get_uniform_location(self.program, "u_slot0");
            let mut out = vec![0.0f32; PROBE_WIDTH * rows * 4];
            for first in (0..PROBE_SLOTS).step_by(buffers) {
                gl.uniform_1_i32(slot0.as_ref(), first as i32);
                gl.draw_arrays(glow::TRIANGLES, 0, 3);
                for i in 0..buffers.min(PROBE_SLOTS - first) {
                    gl.read_buffer(glow::COLOR_ATTACHMENT0 + i as u32);
                    gl.read_pixels(
                        0,
                        0,
                        PROBE_WIDTH as i32,
                        rows as i32,
                        glow::RGBA,
                        glow::FLOAT,
                        glow::PixelPackData::Slice(Some(f32_bytes_mut(&mut out))),
                    );
                    for (r, o) in results.iter_mut().zip(out.chunks_exact(4)) {
                        r[first + i].copy_from_slice(o);
                    }
                }
            }
            gl.delete_texture(texture);
            gl.active_texture(glow::TEXTURE0);
            gl_error(gl, "in a probe")?;
        }
        Ok(results)
    }
}

impl Drop for Prober {
    fn drop(&mut self) {
        let gl = &self.ctx.gl;
        // SAFETY: deleting objects this prober created, on its context.
        unsafe {
            gl.delete_program(self.program);
            for t in &self.targets {
                gl.delete_texture(*t);
            }
            gl.delete_framebuffer(self.framebuffer);
            gl.delete_vertex_array(self.vao);
        }
    }
}

/// A framebuffer with `buffers` RGBA32F render targets of `width` × `height`, left bound.
///
/// # Safety
/// A context must be current on this thread, `gl` its functions.
unsafe fn render_targets(
    gl: &glow::Context,
    buffers: usize,
    width: usize,
    height: usize,
) -> Result<(glow::Framebuffer, Vec<glow::Texture>), HostError> {
    let framebuffer = gl.create_framebuffer().map_err(HostError::Gl)?;
    gl.bind_framebuffer(glow::FRAMEBUFFER, Some(framebuffer));
    let mut targets = Vec::new();
    for i in 0..buffers {
        let t = gl.create_texture().map_err(HostError::Gl)?;
        gl.bind_texture(glow::TEXTURE_2D, Some(t));
        gl.tex_storage_2d(
            glow::TEXTURE_2D,
            1,
            glow::RGBA32F,
            width as i32,
            height as i32,
        );
        gl.framebuffer_texture_2d(
            glow::FRAMEBUFFER,
            glow::COLOR_ATTACHMENT0 + i as u32,
            glow::TEXTURE_2D,
            Some(t),
            0,
        );
        targets.push(t);
    }
    let attachments: Vec<u32> = (0..buffers)
        .map(|i| glow::COLOR_ATTACHMENT0 + i as u32)
        .collect();
    gl.draw_buffers(&attachments);
    if gl.check_framebuffer_status(glow::FRAMEBUFFER) != glow::FRAMEBUFFER_COMPLETE {
        return Err(HostError::Gl("float render targets are incomplete".into()));
    }
    Ok((framebuffer, targets))
}
