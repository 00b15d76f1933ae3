//! The page (HTML, CSS, JavaScript modules), embedded in the binary so that the viewer needs
//! no files beside it and nothing from the internet. The page's folder also holds its type
//! check (tsconfig.json, contract.d.ts, window.d.ts: types only), which is not served.

/// The page's files: (URL path, content type, content).
pub const FILES: [(&str, &str, &str); 20] = [
    (
        "/",
        "text/html; charset=utf-8",
        include_str!("../page/index.html"),
    ),
    (
        "/viewer.css",
        "text/css; charset=utf-8",
        include_str!("../page/viewer.css"),
    ),
    js("/viewer.js", include_str!("../page/viewer.js")),
    js("/api.js", include_str!("../page/api.js")),
    js("/dom.js", include_str!("../page/dom.js")),
    js("/controls.js", include_str!("../page/controls.js")),
    js("/data.js", include_str!("../page/data.js")),
    js("/gl.js", include_str!("../page/gl.js")),
    js("/shaders.js", include_str!("../page/shaders.js")),
    js("/uniforms.js", include_str!("../page/uniforms.js")),
    js("/overlays.js", include_str!("../page/overlays.js")),
    js("/look.js", include_str!("../page/look.js")),
    js("/explore.js", include_str!("../page/explore.js")),
    js("/keep.js", include_str!("../page/keep.js")),
    js("/map.js", include_str!("../page/map.js")),
    js("/trace.js", include_str!("../page/trace.js")),
    js("/traced.js", include_str!("../page/traced.js")),
    js("/fly.js", include_str!("../page/fly.js")),
    js("/hovered.js", include_str!("../page/hovered.js")),
    js("/stereo.js", include_str!("../page/stereo.js")),
];

const fn js(path: &'static str, body: &'static str) -> (&'static str, &'static str, &'static str) {
    (path, "text/javascript; charset=utf-8", body)
}
