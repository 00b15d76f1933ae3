//! The godel crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p godel --test integration render_cli`.

mod browser_support;
mod common;

// First (libtest starts tests in the order of their names): the browser tests are the longest
// (the page's kernels compile on one core, in SwiftShader), and the short ones after them keep
// both cores busy to the end.
mod browser;
mod cli;
mod connect_family_cli;
mod consistency_cli;
mod explore_cli;
mod family_cli;
mod flythrough_cli;
mod gpu_cli;
mod hdr_cli;
mod limits_cli;
mod look_cli;
mod part_merge;
mod render_cli;
mod samples_cli;
mod sequence_cli;
mod server_cli;
mod shade_cli;
mod stereo_cli;
mod symmetry_cli;
mod view_cli;
mod writes_cli;
