//! Tile-level rendering for split and distributed runs: trace any set of the image's
//! tiles into [`TileData`], and put tiles into (or take them out of) a [`DataFile`].
//!
//! A tile's records depend only on the scene and the tile (see `driver::trace_tile`), so
//! an image assembled from tiles traced anywhere, in any order, equals the one
//! `driver::render` makes, byte for byte once written. Light planes (`DataFile::lights`)
//! travel with each tile, so parts, merges and MPI runs carry them generically.

use crate::datafile::DataFile;
use crate::driver::{build_tracer, header, tiles, trace_tile_lit, Progress, RenderError};
use crate::record::{PixelRecord, RayStatus};
use crate::tracer::Tracer;
use rayon::prelude::*;
use scene::Scene;

pub use crate::driver::Tile;

/// What tracing one tile produced: its records (row-major within the tile) and one plane
/// of light values per light source (same order).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TileData {
    /// Index of the tile in [`TileRenderer::tiles`].
    pub index: usize,
    pub records: Vec<PixelRecord>,
    pub lights: Vec<Vec<f32>>,
}

/// A scene's tracer and tile list, ready to trace any subset of the tiles.
pub struct TileRenderer<'a> {
    scene: &'a Scene,
    tracer: Tracer,
    tiles: Vec<Tile>,
}

impl<'a> TileRenderer<'a> {
    pub fn new(scene: &'a Scene) -> Result<TileRenderer<'a>, RenderError> {
        Ok(TileRenderer {
            scene,
            tracer: build_tracer(scene)?,
            tiles: image_tiles(scene),
        })
    }

    /// All tiles of the image, in the driver's (row-major) order.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// Traces the tiles with these indices on rayon's current pool, in parallel.
    pub fn trace(&self, indices: &[usize], progress: &dyn Progress) -> Vec<TileData> {
        indices
            .par_iter()
            .map_init(
                || self.tracer.scratch(),
                |scratch, &index| {
                    let tile = self.tiles[index];
                    let (records, lit) = trace_tile_lit(self.scene, &self.tracer, tile, scratch);
                    progress.advance(records.len() as u64);
                    // Pixel-major light values (one per source) into one plane per source.
                    let n = self.scene.lights.len();
                    let lights = (0..n)
                        .map(|k| (0..records.len()).map(|i| lit[i * n + k]).collect())
                        .collect();
                    TileData {
                        index,
                        records,
                        lights,
                    }
                },
            )
            .collect()
    }

    /// The scene's data file with no pixel traced yet (status "not traced").
    pub fn blank(&self) -> DataFile {
        blank(self.scene)
    }
}

/// The tiles of a scene's image.
pub fn image_tiles(scene: &Scene) -> Vec<Tile> {
    tiles(scene.camera.width(), scene.camera.height())
}

/// The scene's data file with no pixel traced yet (status "not traced", no light planes).
pub fn blank(scene: &Scene) -> DataFile {
    let (w, h) = (
        scene.camera.width() as usize,
        scene.camera.height() as usize,
    );
    DataFile {
        header: header(scene),
        width: w,
        height: h,
        records: vec![PixelRecord::miss(RayStatus::NotTraced); w * h],
        lights: vec![],
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
