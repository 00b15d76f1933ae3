//! The viewer crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p viewer --test integration explore`.

mod common;
mod contract_types;
mod gpu_common;

mod api;
mod contract;
mod explore;
mod gpu_api;
mod gpu_guard;
mod guard;
mod keep;
mod kernel_api;
mod limits;
mod page_files;
mod server;
mod stereo;
mod textures;
