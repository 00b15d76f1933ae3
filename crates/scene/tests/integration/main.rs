//! The scene crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p scene --test integration validation`.

mod input_files;
mod no_panic;
mod scene_files;
mod stereo;
mod validation;
mod view_edit;
