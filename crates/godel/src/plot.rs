//! What `godel plot` draws with (`crate::cmd::plot` is the command): the figures' common
//! parts (axes, legends, colours: `kit`), the SVG writer and its PNG rendering (`svg`), and
//! the isometry figure (`isometry`) and the light rays of the Gödel-type family (`family`).

pub mod family;
pub mod isometry;
pub mod kit;
pub mod svg;
