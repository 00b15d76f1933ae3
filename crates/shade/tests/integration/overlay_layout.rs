//! Marks never collide: the overlay layer's labels (orientation marks, the travel-time legend,
//! the reference squares' labels) never overlap one another or a reference square and never
//! leave the picture, for every camera kind and picture sizes from 240×60 to 3840×2160, with
//! every overlay switched on; each mark label stays beside its own tick, and the labels'
//! ink stays inside their boxes.

use image::RgbaImage;
use scene::Camera;
use shade::layer::{Kind, Overlays, Piece};
use shade::legend::reference_rects;
use shade::marks::{bottom_band, ticks, Axis};
use shade::placement::Rect;

/// Every camera kind, with the sizes its pictures come in (a fisheye's are square).
fn cases() -> Vec<(Camera, Vec<(u32, u32)>)> {
    let wide = vec![
        (240, 60),
        (320, 80),
        (480, 90),
        (720, 120),
        (880, 100),
        (1320, 150),
        (1440, 240),
        (1440, 360),
        (1920, 1080),
        (2560, 1440),
        (3840, 2160),
    ];
    let pictures = vec![
        (240, 60),
        (240, 160),
        (640, 360),
        (1024, 768),
        (1920, 1080),
        (3840, 2160),
    ];
    let spheres = vec![(240, 120), (720, 360), (2048, 1024), (3840, 1920)];
    let squares = vec![
        (60, 60),
        (120, 120),
        (240, 240),
        (512, 512),
        (1080, 1080),
        (2160, 2160),
    ];
    let panorama = |h_fov_deg, v_fov_deg| Camera::Panorama {
        h_fov_deg,
        v_fov_deg,
        width: 1,
        height: 1,
    };
    vec![
        (panorama(220.0, 25.0), wide.clone()),
        (panorama(360.0, 60.0), wide.clone()),
        (panorama(360.0, 90.0), wide),
        (
            Camera::Sphere {
                width: 1,
                height: 1,
            },
            spheres,
        ),
        (
            Camera::Pinhole {
                fov_deg: 90.0,
                width: 1,
                height: 1,
            },
            pictures.clone(),
        ),
        (
            Camera::Pinhole {
                fov_deg: 20.0,
                width: 1,
                height: 1,
            },
            pictures,
        ),
        (
            Camera::Fisheye {
                fov_deg: 180.0,
                size: 1,
            },
            squares.clone(),
        ),
        (
            Camera::Fisheye {
                fov_deg: 360.0,
                size: 1,
            },
            squares,
        ),
    ]
}

fn everything(camera: Camera) -> Overlays {
    Overlays {
        marks: Some(camera),
        legend: Some((0.0, 12.5)),
        polarization: true,
        reference_labels: vec![5800.0, 3500.0],
    }
}

fn text(p: &Piece) -> String {
    p.label().map_or("legend".into(), |l| l.text.clone())
}

#[test]
fn no_label_overlaps_another_or_leaves_the_picture() {
    let mut checked = 0;
    for (camera, sizes) in cases() {
        for (w, h) in sizes {
            let pieces = everything(camera).layout(w, h);
            let squares = reference_rects(2, w, h);
            for (i, p) in pieces.iter().enumerate() {
                assert!(
                    p.rect.inside(i64::from(w), i64::from(h)),
                    "{camera:?} {w}×{h}: {} at {:?} leaves the picture",
                    text(p),
                    p.rect
                );
                for q in &pieces[i + 1..] {
                    assert!(
                        !p.rect.near(&q.rect, 1),
                        "{camera:?} {w}×{h}: {} at {:?} and {} at {:?} touch",
                        text(p),
                        p.rect,
                        text(q),
                        q.rect
                    );
                }
                for s in &squares {
                    assert!(
                        !p.rect.near(s, 1),
                        "{camera:?} {w}×{h}: {} on a square",
                        text(p)
                    );
                }
                checked += 1;
            }
            // The marks still say something: at least two azimuths on every picture at least
            // 240 pixels wide (and tall, for a fisheye, whose labels run along its middle).
            let azimuths = pieces
                .iter()
                .filter(|p| p.kind == Kind::Mark(Axis::Azimuth))
                .count();
            let fisheye = matches!(camera, Camera::Fisheye { .. });
            if w >= 240 && (!fisheye || h >= 240) {
                assert!(
                    azimuths >= 2,
                    "{camera:?} {w}×{h}: {azimuths} azimuth labels"
                );
            }
            // The legend and the temperatures find room from 480 pixels wide on.
            if w >= 480 && h >= 90 {
                for kind in [Kind::Legend, Kind::ReferenceLabel] {
                    assert!(
                        pieces.iter().any(|p| p.kind == kind),
                        "{camera:?} {w}×{h}: no {kind:?}"
                    );
                }
            }
        }
    }
    assert!(checked > 500, "{checked} pieces");
}

#[test]
fn each_mark_label_sits_beside_its_own_tick() {
    for (camera, sizes) in cases() {
        let fisheye = matches!(camera, Camera::Fisheye { .. });
        for (w, h) in sizes {
            let ticks = ticks(&camera.with_size(w, h));
            for p in everything(camera).layout(w, h) {
                let Kind::Mark(axis) = p.kind else { continue };
                let tick = ticks
                    .iter()
                    .find(|t| t.axis == axis && t.label == text(&p))
                    .unwrap_or_else(|| panic!("{camera:?} {w}×{h}: no tick for {}", text(&p)));
                let (col, row) = (i64::from(tick.col), i64::from(tick.row));
                let r = p.rect;
                // Along the axis the label is centred on its tick, unless it was moved in
                // from the picture's edge; across, it is beside the tick.
                let (along, lo, hi, extent) = match (axis, fisheye) {
                    (Axis::Azimuth, _) => (col, r.x0, r.x1, i64::from(w)),
                    (Axis::Elevation, _) => (row, r.y0, r.y1, i64::from(h)),
                };
                assert!(
                    (lo <= along && along < hi) || lo == 0 || hi == extent,
                    "{camera:?} {w}×{h}: {} at {r:?} is not at its tick ({col}, {row})",
                    text(&p)
                );
                let beside = match (axis, fisheye) {
                    (Axis::Azimuth, false) => r.y1 < i64::from(h) && r.y0 > i64::from(h) / 2,
                    (Axis::Elevation, false) => r.x0 > 0 && r.x1 < i64::from(w) / 2,
                    (Axis::Azimuth, true) => r.y0 > row || r.y1 == i64::from(h),
                    (Axis::Elevation, true) => r.x0 > col,
                };
                assert!(beside, "{camera:?} {w}×{h}: {} at {r:?}", text(&p));
            }
        }
    }
}

/// The bug of the README's first picture (1320×150, 220°×25°): the elevation label "−10°"
/// sat in the row of the azimuth labels, beside "−90°". Elevation labels now stay above that
/// row, and the labels are drawn inside their boxes.
#[test]
fn elevation_labels_stay_out_of_the_azimuth_row() {
    for (camera, sizes) in cases() {
        if matches!(camera, Camera::Fisheye { .. }) {
            continue;
        }
        for (w, h) in sizes {
            let floor = i64::from(h) - i64::from(bottom_band(&camera, w, h));
            for p in everything(camera).layout(w, h) {
                if p.kind == Kind::Mark(Axis::Elevation) {
                    assert!(p.rect.y1 <= floor, "{camera:?} {w}×{h}: {}", text(&p));
                }
            }
        }
    }
    let reference = Camera::Panorama {
        h_fov_deg: 220.0,
        v_fov_deg: 25.0,
        width: 1320,
        height: 150,
    };
    let marks = Overlays {
        marks: Some(reference),
        ..Overlays::default()
    };
    let labels: Vec<String> = marks.layout(1320, 150).iter().map(text).collect();
    for want in ["−90°", "0°", "90°", "10°"] {
        assert!(labels.contains(&want.to_string()), "{want} in {labels:?}");
    }
    assert!(!labels.contains(&"−10°".to_string()), "{labels:?}");
    // Ink only where a piece, a tick or the grid is: clear a copy inside the pieces' boxes and
    // at the ticks and grid lines, and nothing white is left.
    let layer = marks.draw(1320, 150).unwrap();
    let grid_and_ticks = {
        let mut l = RgbaImage::new(1320, 150);
        shade::marks::draw_grid_and_ticks(&mut l, &reference);
        l
    };
    let boxes: Vec<Rect> = marks.layout(1320, 150).iter().map(|p| p.rect).collect();
    for (x, y, p) in layer.enumerate_pixels() {
        let here = Rect::at(i64::from(x), i64::from(y), 1, 1);
        if boxes.iter().any(|b| b.near(&here, 0)) {
            continue;
        }
        assert_eq!(
            p,
            grid_and_ticks.get_pixel(x, y),
            "({x}, {y}): drawn outside every label's box"
        );
    }
}
