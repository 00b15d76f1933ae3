//! Orientation marks sit where the camera looks: every tick's pixel is checked against the
//! camera's forward mapping (`Camera::pixel_direction`), and panorama ticks also against the
//! panorama's closed form (column = (az/h_fov + ½)·width).

use image::RgbaImage;
use scene::{azimuth_elevation, Camera};
use shade::marks::{draw_grid_and_ticks, ticks, Axis, MARK_COLOUR};

fn cameras() -> Vec<Camera> {
    vec![
        Camera::Panorama {
            h_fov_deg: 220.0,
            v_fov_deg: 25.0,
            width: 880,
            height: 100,
        },
        Camera::Sphere {
            width: 720,
            height: 360,
        },
        Camera::Fisheye {
            fov_deg: 180.0,
            size: 400,
        },
        Camera::Pinhole {
            fov_deg: 90.0,
            width: 640,
            height: 360,
        },
    ]
}

/// Azimuth and elevation (degrees) where pixel (col, row) looks.
fn angles(c: &Camera, col: u32, row: u32) -> (f64, f64) {
    azimuth_elevation(c.pixel_direction(col, row).expect("a traced pixel"))
}

#[test]
fn each_tick_sits_within_a_pixel_of_its_angle() {
    for c in cameras() {
        let ts = ticks(&c);
        assert!(
            ts.iter().filter(|t| t.axis == Axis::Azimuth).count() >= 3
                && ts.iter().filter(|t| t.axis == Axis::Elevation).count() >= 2,
            "{c:?}: {ts:?}"
        );
        for t in &ts {
            let (az, el) = angles(&c, t.col, t.row);
            // One pixel's worth of angle, measured with the neighbouring pixel.
            let (value, step) = match t.axis {
                Axis::Azimuth => {
                    let n = if t.col + 1 < c.width() {
                        t.col + 1
                    } else {
                        t.col - 1
                    };
                    (az, (angles(&c, n, t.row).0 - az).abs())
                }
                Axis::Elevation => {
                    let n = if t.row + 1 < c.height() {
                        t.row + 1
                    } else {
                        t.row - 1
                    };
                    (el, (angles(&c, t.col, n).1 - el).abs())
                }
            };
            // ±180° are the same azimuth.
            let mut diff = (value - t.degrees).abs();
            if t.axis == Axis::Azimuth {
                diff = diff.min(360.0 - diff);
            }
            assert!(
                diff <= step + 1e-9,
                "{c:?}: tick {} at ({}, {}) looks at {value:.3}° (one pixel = {step:.3}°)",
                t.label,
                t.col,
                t.row
            );
            // Whole degrees, negative ones with the minus sign U+2212.
            let d = t.degrees.round() as i64;
            let sign = if d < 0 { "\u{2212}" } else { "" };
            assert_eq!(t.label, format!("{sign}{}°", d.abs()));
        }
    }
}

#[test]
fn panorama_ticks_match_the_closed_form_and_are_drawn() {
    let c = cameras()[0];
    let ts = ticks(&c);
    let az30 = ts
        .iter()
        .find(|t| t.axis == Axis::Azimuth && t.degrees == 30.0)
        .expect("a 30° tick on a 220° panorama");
    let col = ((30.0 / 220.0 + 0.5) * 880.0f64).floor() as u32;
    assert_eq!((az30.col, az30.row), (col, 99));
    // Left of the centre is negative azimuth.
    let left = ts
        .iter()
        .find(|t| t.axis == Axis::Azimuth && t.degrees == -30.0)
        .unwrap();
    assert!(left.col < 440 && az30.col > 440);
    // Upper elevation ticks are above the horizon row.
    let up = ts
        .iter()
        .find(|t| t.axis == Axis::Elevation && t.degrees > 0.0)
        .unwrap();
    assert!(up.row < 50);

    let mut img = RgbaImage::new(880, 100);
    draw_grid_and_ticks(&mut img, &c);
    for t in &ts {
        assert_eq!(
            img.get_pixel(t.col, t.row).0[..3],
            MARK_COLOUR,
            "{}",
            t.label
        );
        assert_eq!(img.get_pixel(t.col, t.row).0[3], 255, "{}", t.label);
    }
}

#[test]
fn marks_follow_the_picture_size() {
    // A picture shown at twice the traced size gets the ticks of the resized camera.
    let c = cameras()[1];
    let big = c.with_size(1440, 720);
    let mut img = RgbaImage::new(1440, 720);
    draw_grid_and_ticks(&mut img, &c);
    for t in ticks(&big) {
        assert_eq!(
            img.get_pixel(t.col, t.row).0[..3],
            MARK_COLOUR,
            "{}",
            t.label
        );
    }
    // Too small a picture is left alone.
    let mut tiny = RgbaImage::new(8, 8);
    draw_grid_and_ticks(&mut tiny, &c);
    assert!(tiny.pixels().all(|p| p.0 == [0, 0, 0, 0]));
}
