//! The memory of a look picture (issue 24: one `/api/look/image` at 3840×2160 took ~1.1 GB
//! transient even from a small sphere, and 200 such requests at once peaked at 2.6 GB): the
//! picture is remapped and shaded in bands of rows, so a 4K view takes its RGB bytes, one
//! band's records and its answer, well under 200 MB. Measured here with a counting
//! allocator around the system's: the peak of the bytes allocated while one request is
//! answered.
//!
//! A binary of its own: the counting allocator is the whole process's, and the tests of the
//! integration binary, running beside this one on other threads, would add to its peak.

// Shared with the integration binary, which uses all of it; `pub` so that what this test
// leaves unused is not reported as dead.
#[path = "integration/gpu_common.rs"]
pub mod gpu_common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use axum::http::StatusCode;

/// The system allocator, counting the bytes allocated now and their peak.
struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(bytes: usize) {
    let now = NOW.fetch_add(bytes, Ordering::SeqCst) + bytes;
    PEAK.fetch_max(now, Ordering::SeqCst);
}

// SAFETY: every call is passed on to the system allocator unchanged; only counts are added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        NOW.fetch_sub(layout.size(), Ordering::SeqCst);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            NOW.fetch_sub(layout.size(), Ordering::SeqCst);
            grew(new_size);
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[tokio::test]
async fn a_4k_look_picture_takes_far_less_than_200_mb() {
    let state = gpu_common::state_of(gpu_common::data());
    let settings = serde_json::to_value(state.info().defaults).unwrap();
    let body = serde_json::json!({
        "settings": settings,
        "view": {
            "camera": {"kind": "pinhole", "fov_deg": 90.0, "width": 3840, "height": 2160},
            "forward": [1.0, 0.0, 0.0],
            "up": [0.0, 0.0, 1.0],
            "velocity": {"speed": 0.5, "direction": [0.0, 1.0, 0.0]},
        },
    })
    .to_string();
    let request = gpu_common::post("/api/look/image", body);
    let before = NOW.load(Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    let (status, picture) = gpu_common::send_to(state, request).await;
    let peak = PEAK.load(Ordering::SeqCst) - before;
    assert_eq!(status, StatusCode::OK);
    // The answer itself (RGBA, 33 MB) is counted twice: as sent and as collected here.
    assert_eq!(picture.len(), 3840 * 2160 * 4);
    let mb = peak as f64 / 1e6;
    eprintln!("a 4K look picture: {mb:.0} MB at the peak");
    assert!(mb < 150.0, "a 4K look picture took {mb:.0} MB at its peak");
}
