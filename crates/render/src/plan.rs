//! Plans of work: the image's tiles (16×16 pixels, row-major), and which of them a run
//! traces — all of them, part i/N of a split render, an explicit batch (an MPI job), or
//! those touching a sub-rectangle.
//!
//! Parts deal tiles round-robin (tile k goes to part k mod N + 1), not in stripes, so
//! that the costly rays near the horizon spread over all parts.

use std::fmt;
use std::str::FromStr;

/// Tile edge in pixels: small enough to balance rays of very different cost.
const TILE: u32 = 16;

/// The rectangle of pixels of one tile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    pub col0: u32,
    pub row0: u32,
    pub cols: u32,
    pub rows: u32,
}

/// All tiles of a width × height image, in row-major order.
pub fn tiles(width: u32, height: u32) -> Vec<Tile> {
    let mut out = Vec::new();
    for row0 in (0..height).step_by(TILE as usize) {
        for col0 in (0..width).step_by(TILE as usize) {
            out.push(Tile {
                col0,
                row0,
                cols: TILE.min(width - col0),
                rows: TILE.min(height - row0),
            });
        }
    }
    out
}

/// Part `index` (1-based) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Part {
    pub index: u32,
    pub count: u32,
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Part {
    type Err = String;
    fn from_str(s: &str) -> Result<Part, String> {
        let bad = || format!("expected i/N with 1 ≤ i ≤ N (e.g. 2/8), got '{s}'");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: u32 = i.trim().parse().map_err(|_| bad())?;
        let count: u32 = n.trim().parse().map_err(|_| bad())?;
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Part { index, count })
    }
}

impl Part {
    /// Whether tile `k` of the image belongs to this part.
    pub fn has_tile(&self, k: usize) -> bool {
        k % self.count as usize == (self.index - 1) as usize
    }

    /// The indices of this part's tiles among `tile_count` tiles.
    pub fn tiles(&self, tile_count: usize) -> Vec<usize> {
        (0..tile_count).filter(|&k| self.has_tile(k)).collect()
    }

    /// The part file's name for a scene: `NAME.part-I-of-N.exr`.
    pub fn file_name(&self, scene_name: &str) -> String {
        format!("{scene_name}.part-{}-of-{}.exr", self.index, self.count)
    }
}

/// Which tiles a run traces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Plan {
    /// Every tile of the image.
    All,
    /// Part i/N of a split render.
    Part(Part),
    /// These tile indices (e.g. one MPI job).
    Tiles(Vec<usize>),
    /// The tiles that touch the rectangle of `cols` × `rows` pixels at (`col0`, `row0`).
    Rect(Tile),
}

impl Plan {
    /// The indices, ascending, of the planned tiles among `tiles` (out-of-range indices of
    /// an explicit batch are left out).
    pub fn indices(&self, tiles: &[Tile]) -> Vec<usize> {
        match self {
            Plan::All => (0..tiles.len()).collect(),
            Plan::Part(p) => p.tiles(tiles.len()),
            Plan::Tiles(list) => {
                let mut out: Vec<usize> = list.iter().copied().filter(|&k| k < tiles.len()).collect();
                out.sort_unstable();
                out.dedup();
                out
            }
            Plan::Rect(r) => (0..tiles.len())
                .filter(|&k| {
                    let t = tiles[k];
                    t.col0 < r.col0 + r.cols
                        && r.col0 < t.col0 + t.cols
                        && t.row0 < r.row0 + r.rows
                        && r.row0 < t.row0 + t.rows
                })
                .collect(),
        }
    }
}
