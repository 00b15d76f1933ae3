//! The shade crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p shade --test integration shading`.

mod blackbody;
mod channels;
mod frequency_shader;
mod lit_preview;
mod marks;
mod overlay_layout;
mod polarization_layer;
mod script;
mod settings;
mod shade;
mod shading;
mod stereo;
mod texture_source;
