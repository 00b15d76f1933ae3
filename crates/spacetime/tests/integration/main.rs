//! The spacetime crate's integration tests, one binary (ripgrep's layout: the crate is linked
//! once, not once per file). One module: `cargo test -p spacetime --test integration geodesics`.

mod common;

mod closed_form;
mod connect;
mod eyes;
mod geodesics;
mod godel_type;
mod godel_type_connect;
mod godel_type_geodesic;
mod godel_type_symmetry;
mod metric;
mod polarization;
mod symmetry;
mod transport;
