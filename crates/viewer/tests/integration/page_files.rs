//! The page's files (crates/viewer/page) are what the server serves: every module and the
//! page itself, byte for byte (a module missing from `viewer::assets` fails the page's load),
//! and none of the type check's files (tsconfig.json, *.d.ts: types only).

use axum::http::StatusCode;

use crate::common::{get, send};

#[tokio::test]
async fn every_module_of_the_page_is_served_and_its_types_are_not() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("page");
    let mut served = 0;
    for entry in std::fs::read_dir(&folder).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        let url = if name == "index.html" {
            "/".to_string()
        } else {
            format!("/{name}")
        };
        let (status, _, body) = send(get(&url)).await;
        if name.ends_with(".d.ts") || name == "tsconfig.json" {
            assert_eq!(status, StatusCode::NOT_FOUND, "{name} is served");
        } else {
            assert_eq!(status, StatusCode::OK, "{name} is not served");
            assert_eq!(body, std::fs::read(&path).unwrap(), "{name} differs");
            served += 1;
        }
    }
    // index.html, viewer.css and the modules.
    assert!(served >= 19, "{served} files served");
}
