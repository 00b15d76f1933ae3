//! What `godel plot` draws with (`crate::cmd::plot` is the command): the figures' common
//! parts (axes, legends, colours: `kit`), the SVG writer and its PNG rendering (`svg`), and
//! the isometry figure (`isometry`).

pub mod isometry;
pub mod kit;
pub mod svg;
