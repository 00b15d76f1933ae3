//! Traced tiles: [`TileData`] (what tracing one tile produced), the [`Sink`] that receives
//! them, the [`Assembler`] sink that puts tiles into a [`DataFile`], and taking tiles out
//! of one (for merges).
//!
//! A tile's records depend only on the scene and the tile (see `Renderer::trace_tile`), so
//! an image assembled from tiles traced anywhere, in any order, equals a whole render
//! byte for byte once written. Light planes (`DataFile::lights`) travel with each tile, so
//! parts, merges and MPI runs carry them generically.

use crate::plan::Tile;
use datafile::{DataFile, PixelRecord};

/// What tracing one tile produced: its records (row-major within the tile) and one plane
/// of light values per light source (same order).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TileData {
    /// Index of the tile in the image's tiles (`Renderer::tiles`).
    pub index: usize,
    pub records: Vec<PixelRecord>,
    pub lights: Vec<Vec<f32>>,
}

/// Receives finished tiles, in any order (one at a time).
pub trait Sink {
    fn accept(&mut self, tile: TileData);
}

/// The sink that puts traced tiles into a data file.
pub struct Assembler {
    data: DataFile,
    tiles: Vec<Tile>,
}

impl Assembler {
    /// Fills `data` (usually `Renderer::blank`) with the tiles of `tiles` as they come.
    pub fn new(data: DataFile, tiles: &[Tile]) -> Assembler {
        Assembler {
            data,
            tiles: tiles.to_vec(),
        }
    }

    /// The data file with every tile received so far.
    pub fn finish(self) -> DataFile {
        self.data
    }
}

impl Sink for Assembler {
    fn accept(&mut self, tile: TileData) {
        insert(&mut self.data, self.tiles[tile.index], &tile);
    }
}

/// A sink that keeps the tiles as they are.
impl Sink for Vec<TileData> {
    fn accept(&mut self, tile: TileData) {
        self.push(tile);
    }
}

/// Image indices of the pixels of `tile`, row-major within the tile.
pub fn pixel_indices(tile: Tile, width: usize) -> impl Iterator<Item = usize> {
    (tile.row0..tile.row0 + tile.rows).flat_map(move |row| {
        (tile.col0..tile.col0 + tile.cols).map(move |col| row as usize * width + col as usize)
    })
}

/// Copies a traced tile into `data`; light planes missing in `data` are added (zero).
pub fn insert(data: &mut DataFile, tile: Tile, traced: &TileData) {
    let pixels = data.width * data.height;
    while data.lights.len() < traced.lights.len() {
        data.lights.push(vec![0.0; pixels]);
    }
    for (k, i) in pixel_indices(tile, data.width).enumerate() {
        data.records[i] = traced.records[k];
        for (plane, values) in data.lights.iter_mut().zip(&traced.lights) {
            plane[i] = values[k];
        }
    }
}

/// The records and light values of one tile of `data`.
pub fn extract(data: &DataFile, tile: Tile, index: usize) -> TileData {
    let at: Vec<usize> = pixel_indices(tile, data.width).collect();
    TileData {
        index,
        records: at.iter().map(|&i| data.records[i]).collect(),
        lights: data
            .lights
            .iter()
            .map(|plane| at.iter().map(|&i| plane[i]).collect())
            .collect(),
    }
}
