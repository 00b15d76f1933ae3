//! The subcommands of `godel`, one module each: its arguments (clap) and its `run`.

pub mod connect;
pub mod explore;
pub mod geodesic;
pub mod look;
pub mod merge;
pub mod plot;
pub mod render;
pub mod sequence;
pub mod shade;
pub mod view;
