//! Cancelling a render (`Progress::cancelled`, used by `godel explore` when a newer event
//! comes): the driver traces no tile after the flag is set, and the tiles it did trace are
//! those of the whole render.

use crate::common::*;
use render::driver::{Progress, Renderer};
use render::plan::Plan;
use render::tiles::TileData;
use std::sync::atomic::{AtomicU64, Ordering};

/// Reports cancelled once `after` pixels are done.
struct CancelAfter {
    done: AtomicU64,
    after: u64,
}

impl Progress for CancelAfter {
    fn advance(&self, pixels: u64) {
        self.done.fetch_add(pixels, Ordering::SeqCst);
    }
    fn cancelled(&self) -> bool {
        self.done.load(Ordering::SeqCst) >= self.after
    }
}

fn trace(renderer: &Renderer, after: u64) -> Vec<TileData> {
    let progress = CancelAfter {
        done: AtomicU64::new(0),
        after,
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| renderer.trace(&Plan::All, &progress))
}

#[test]
fn a_cancelled_render_stops_after_the_tile_under_way() {
    let s = scene(&testkit::axis_panorama("cancel", 64, 32, 8.0, ""));
    let renderer = Renderer::new(&s).unwrap();
    let all = renderer.tiles().len();
    assert!(all >= 4, "{all} tiles");
    // Never cancelled: every tile.
    let whole = trace(&renderer, u64::MAX);
    assert_eq!(whole.len(), all);
    // Cancelled after the first pixel: one thread traces the first tile, then stops.
    let cut = trace(&renderer, 1);
    assert_eq!(cut.len(), 1);
    let same = whole.iter().find(|t| t.index == cut[0].index).unwrap();
    assert_eq!(&cut[0], same);
    // Cancelled from the start: nothing.
    assert!(trace(&renderer, 0).is_empty());
}
