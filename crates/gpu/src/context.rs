//! An offscreen OpenGL ES 3 context through EGL, with libEGL loaded at run time: godel runs
//! where no EGL is installed, and only `--gpu` needs it. The display is Mesa's surfaceless
//! platform where there is one (a GPU driver of Mesa, or llvmpipe, its software renderer,
//! where there is no GPU), else the first EGL device (NVIDIA's headless driver), else the
//! default display; the context has no surface (EGL_KHR_surfaceless_context): the kernel
//! draws into framebuffer objects.

use khronos_egl as egl;
use std::sync::Mutex;

/// The EGL library's file names tried in turn, unless the environment variable [`LIBRARY_VAR`]
/// names one (a path, for an EGL installed out of the loader's way; empty is unset).
const LIBRARIES: [&str; 2] = ["libEGL.so.1", "libEGL.so"];
pub const LIBRARY_VAR: &str = "GODEL_EGL";

/// EGL_PLATFORM_SURFACELESS_MESA and EGL_PLATFORM_DEVICE_EXT.
const PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;
const PLATFORM_DEVICE_EXT: egl::Enum = 0x313F;

/// Why no context could be made: each says in one sentence what tracing on the GPU needs
/// (the caller says what asked for it: `--gpu`, or a scene's `[trace] gpu = true`).
#[derive(Debug, thiserror::Error)]
pub enum ContextError {
    #[error("tracing on the GPU needs the EGL library (libEGL.so.1) with OpenGL ES 3, and none could be loaded ({0}); install Mesa's EGL (Debian: libegl1 libegl-mesa0 libgles2), or a GPU driver that brings one")]
    NoLibrary(String),
    #[error("tracing on the GPU found the EGL library but no display it could initialize ({0}); install Mesa's EGL (Debian: libegl-mesa0) for its software renderer llvmpipe")]
    NoDisplay(String),
    #[error("tracing on the GPU could not create an OpenGL ES 3 context on {display} ({why})")]
    NoContext { display: String, why: String },
    #[error(
        "tracing on the GPU needs float render targets (GL_EXT_color_buffer_float), which {0} does not offer"
    )]
    NoFloatTargets(String),
}

type Egl = egl::DynamicInstance<egl::EGL1_4>;

/// The contexts alive in this process, counted under the lock that making or dropping one
/// holds. EGL gives every caller the same display, and eglTerminate on it takes the driver
/// from under any other thread's context (Mesa crashed so when tests traced on several
/// threads at once): the display is terminated only when its last context goes. Contexts on
/// several threads (each current on its own) run at once: llvmpipe compiles a kernel on one
/// core for seconds, and a second thread's compiles or draws need not wait for it.
static LIVE: Mutex<usize> = Mutex::new(0);

/// A current offscreen OpenGL ES 3 context and its GL functions.
pub struct Context {
    pub gl: glow::Context,
    /// What drew: the GL renderer string (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
    pub renderer: String,
    /// How many render targets one draw may fill (at least 4 in OpenGL ES 3).
    pub draw_buffers: usize,
    egl: Egl,
    display: egl::Display,
    context: egl::Context,
}

impl Context {
    /// Loads libEGL, opens a display and makes an OpenGL ES 3.0 context current on this
    /// thread ([`LIVE`]: other threads may hold contexts of their own meanwhile). A thread
    /// holds one context at a time: making a second one current leaves the first without a
    /// thread.
    pub fn new() -> Result<Context, ContextError> {
        // Poisoned (a panic while another thread held it), the count is still right: it
        // changes only after the EGL calls it counts.
        let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
        let egl = load()?;
        let display = open_display(&egl)?;
        let made = Context::make(&egl, display);
        if made.is_err() && *live == 0 {
            let _ = egl.terminate(display);
        }
        let (gl, context) = made?;
        *live += 1;
        drop(live);
        use glow::HasContext;
        // SAFETY: plain queries on the context current on this thread.
        let (renderer, draw_buffers, float_targets) = unsafe {
            let renderer = gl.get_parameter_string(glow::RENDERER);
            let buffers = gl.get_parameter_i32(glow::MAX_DRAW_BUFFERS).clamp(1, 8) as usize;
            let float = (0..gl.get_parameter_i32(glow::NUM_EXTENSIONS)).any(|i| {
                gl.get_parameter_indexed_string(glow::EXTENSIONS, i as u32)
                    == "GL_EXT_color_buffer_float"
            });
            (renderer, buffers, float)
        };
        // Dropped on refusal, it is counted out and its display terminated if it was the last.
        let ctx = Context {
            gl,
            renderer,
            draw_buffers,
            egl,
            display,
            context,
        };
        if !float_targets {
            return Err(ContextError::NoFloatTargets(ctx.renderer.clone()));
        }
        Ok(ctx)
    }

    /// Initializes `display` (a no-op where another context has) and makes a context on it
    /// current on this thread, with its GL functions.
    fn make(
        egl: &Egl,
        display: egl::Display,
    ) -> Result<(glow::Context, egl::Context), ContextError> {
        let (major, minor) = egl
            .initialize(display)
            .map_err(|e| ContextError::NoDisplay(e.to_string()))?;
        let vendor = egl
            .query_string(Some(display), egl::VENDOR)
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let described = format!("EGL {major}.{minor} ({vendor})");
        let fail = |why: String| ContextError::NoContext {
            display: described.clone(),
            why,
        };
        egl.bind_api(egl::OPENGL_ES_API)
            .map_err(|e| fail(format!("OpenGL ES: {e}")))?;
        let config = egl
            .choose_first_config(
                display,
                &[
                    egl::RENDERABLE_TYPE,
                    egl::OPENGL_ES3_BIT,
                    egl::SURFACE_TYPE,
                    egl::PBUFFER_BIT,
                    egl::NONE,
                ],
            )
            .map_err(|e| fail(e.to_string()))?
            .ok_or_else(|| fail("no OpenGL ES 3 configuration".into()))?;
        let context = egl
            .create_context(
                display,
                config,
                None,
                &[
                    egl::CONTEXT_MAJOR_VERSION,
                    3,
                    egl::CONTEXT_MINOR_VERSION,
                    0,
                    egl::NONE,
                ],
            )
            .map_err(|e| fail(e.to_string()))?;
        egl.make_current(display, None, None, Some(context))
            .map_err(|e| fail(format!("surfaceless context: {e}")))?;
        // SAFETY: the context is current on this thread; the loader returns EGL's own
        // function pointers for the names GL asks for.
        let gl = unsafe {
            glow::Context::from_loader_function(|name| {
                egl.get_proc_address(name)
                    .map_or(std::ptr::null(), |p| p as *const _)
            })
        };
        Ok((gl, context))
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
        let _ = self.egl.make_current(self.display, None, None, None);
        let _ = self.egl.destroy_context(self.display, self.context);
        *live = live.saturating_sub(1);
        if *live == 0 {
            let _ = self.egl.terminate(self.display);
        }
    }
}

fn load() -> Result<Egl, ContextError> {
    let mut errors = Vec::new();
    // Empty is unset: dlopen("") would load the running program itself as "libEGL".
    let names: Vec<String> = match std::env::var(LIBRARY_VAR) {
        Ok(name) if !name.trim().is_empty() => vec![name],
        _ => LIBRARIES.iter().map(|s| s.to_string()).collect(),
    };
    for name in &names {
        // SAFETY: loading libEGL runs its initializers, as linking it would; its symbols
        // are looked up with their EGL 1.4 signatures by khronos-egl.
        match unsafe { Egl::load_required_from_filename(name) } {
            Ok(egl) => return Ok(egl),
            Err(e) => errors.push(format!("{name}: {e}")),
        }
    }
    Err(ContextError::NoLibrary(errors.join("; ")))
}

fn open_display(egl: &Egl) -> Result<egl::Display, ContextError> {
    let client = egl
        .query_string(None, egl::EXTENSIONS)
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let get_platform_display = egl.get_proc_address("eglGetPlatformDisplayEXT");
    if let Some(f) = get_platform_display {
        // SAFETY: eglGetPlatformDisplayEXT(platform, native display, attributes) per
        // EGL_EXT_platform_base, whose presence the function pointer shows.
        let gpd: extern "system" fn(
            egl::Enum,
            *mut std::ffi::c_void,
            *const egl::Int,
        ) -> egl::EGLDisplay = unsafe { std::mem::transmute(f) };
        let none = [egl::NONE];
        if client.contains("EGL_MESA_platform_surfaceless") {
            let d = gpd(
                PLATFORM_SURFACELESS_MESA,
                std::ptr::null_mut(),
                none.as_ptr(),
            );
            if !d.is_null() {
                // SAFETY: a display handle EGL itself returned.
                return Ok(unsafe { egl::Display::from_ptr(d) });
            }
        }
        if client.contains("EGL_EXT_platform_device") {
            if let Some(q) = egl.get_proc_address("eglQueryDevicesEXT") {
                // SAFETY: eglQueryDevicesEXT(max, devices, count) per EGL_EXT_device_enumeration.
                let query: extern "system" fn(
                    egl::Int,
                    *mut *mut std::ffi::c_void,
                    *mut egl::Int,
                ) -> egl::Boolean = unsafe { std::mem::transmute(q) };
                let mut devices = [std::ptr::null_mut(); 8];
                let mut count: egl::Int = 0;
                if query(8, devices.as_mut_ptr(), &mut count) == egl::TRUE && count > 0 {
                    let d = gpd(PLATFORM_DEVICE_EXT, devices[0], none.as_ptr());
                    if !d.is_null() {
                        // SAFETY: as above.
                        return Ok(unsafe { egl::Display::from_ptr(d) });
                    }
                }
            }
        }
    }
    // SAFETY: EGL_DEFAULT_DISPLAY is always a valid argument.
    unsafe { egl.get_display(egl::DEFAULT_DISPLAY) }
        .ok_or_else(|| ContextError::NoDisplay("no display on any platform".into()))
}
