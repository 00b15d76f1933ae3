//! The page (HTML, CSS, JavaScript), embedded in the binary so that the viewer needs no
//! files beside it and nothing from the internet.

/// The page's files: (URL path, content type, content).
pub const FILES: [(&str, &str, &str); 3] = [
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
    (
        "/viewer.js",
        "text/javascript; charset=utf-8",
        include_str!("../page/viewer.js"),
    ),
];
