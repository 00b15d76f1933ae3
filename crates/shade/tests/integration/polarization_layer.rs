//! The polarization layer (issue 25): ticks along the observed polarization of the objects
//! whose light the scene (or the settings) polarizes, coloured by the angle on a cyclic map,
//! with a legend; the same bytes from the records and from the channel copy; bad settings and
//! data files without the channels refused naming the field.

use datafile::{DataFile, PixelRecord};
use shade::polarization::{cyclic_colour, tick_spacing};
use shade::{Channels, ShadeSettings, ShaderKind, Shading};
use testkit::hit;

/// A ball polarized along its body axis y, and an unpolarized moon.
fn scene() -> String {
    format!(
        "name = \"pol\"\n{}{}polarization = {{ axis = [0, 2, 0] }}\n{}",
        testkit::panorama(220.0, 25.0, 96, 48),
        testkit::textured_ball_at("ball", 0.1, &testkit::checker(4, 8), 4000.0, 1.0, 0.0),
        testkit::textured_ball_at("moon", 0.1, &testkit::checker(4, 8), 4000.0, 1.0, 2.0),
    )
}

/// 96×48 pixels: the left half the ball, the right half the moon, every photon leaving along
/// body x with the screen-up arriving as body z (screen-right as pol × dir = body y).
fn data(polarization: bool) -> DataFile {
    let (w, h) = (96usize, 48usize);
    let records = (0..w * h)
        .map(|i| {
            let c = i % w;
            let mut r = hit(i32::from(c >= w / 2), 0.3, 0.5, 1.0, -1.0, 0.8);
            r.dir = [1.0, 0.0, 0.0];
            r.pol = [0.0, 0.0, 1.0];
            r
        })
        .collect::<Vec<PixelRecord>>();
    DataFile {
        header: testkit::godel_header("pol", &scene(), "panorama", &["ball", "moon"]),
        width: w,
        height: h,
        records,
        lights: vec![],
        polarization,
    }
}

fn settings(data: &DataFile, shaders: Vec<ShaderKind>) -> ShadeSettings {
    let mut s = ShadeSettings::defaults_for(data);
    s.shaders = shaders;
    s
}

#[test]
fn ticks_follow_the_observed_angle_on_polarized_objects_only() {
    let d = data(true);
    let s = settings(&d, vec![ShaderKind::Polarization]);
    assert_eq!(s.objects["ball"].polarization, Some([0.0, 2.0, 0.0]));
    assert_eq!(s.objects["moon"].polarization, None);
    let shading = Shading::new(&d, &s).unwrap();
    let img = shading.image(&d);
    // Alone, the layer draws over the texture layer's picture.
    let plain = Shading::new(&d, &settings(&d, vec![ShaderKind::Texture]))
        .unwrap()
        .image(&d);
    let step = tick_spacing(96, 48) as u32;
    assert_eq!(step, 12);
    // Axis y is the screen-right: a horizontal tick at 90°, cyan, at each cell centre of
    // the ball's half; the moon's half, unpolarized, has no ticks.
    let cyan = cyclic_colour(std::f64::consts::FRAC_PI_2);
    let (cx, cy) = (step / 2 + step, step / 2 + step);
    assert_eq!(img.get_pixel(cx + 3, cy).0, cyan);
    assert_eq!(img.get_pixel(cx, cy + 3).0, plain.get_pixel(cx, cy + 3).0);
    let (mx, my) = (48 + step / 2 + step, cy);
    for dx in 0..step {
        assert_eq!(
            img.get_pixel(mx + dx - 5, my).0,
            plain.get_pixel(mx + dx - 5, my).0
        );
    }
    let changed = |a: &image::RgbImage| {
        a.pixels()
            .zip(plain.pixels())
            .filter(|(p, q)| p.0 != q.0)
            .count()
    };
    assert!(changed(&img) > 100);
    // The same bytes from the channels.
    let channels = Channels::new(&d, shading.needs());
    assert_eq!(shading.image_with(&channels), img);
    // The settings turn the axis to body z, the screen-up: vertical ticks at 0°, red.
    let mut s2 = s.clone();
    s2.objects.get_mut("ball").unwrap().polarization = Some([0.0, 0.0, 1.0]);
    let img2 = Shading::new(&d, &s2).unwrap().image(&d);
    assert_eq!(img2.get_pixel(cx, cy + 3).0, cyclic_colour(0.0));
    assert_eq!(img2.get_pixel(cx + 3, cy).0, plain.get_pixel(cx + 3, cy).0);
    // With the legend: shown only where an object is polarized.
    assert!(shading.overlays_shown().polarization);
    s2.objects.get_mut("ball").unwrap().polarization = None;
    let none = Shading::new(&d, &s2).unwrap();
    assert!(!none.overlays_shown().polarization);
    assert_eq!(none.image(&d), plain);
}

#[test]
fn the_legend_is_a_cyclic_bar_with_its_title() {
    let overlays = shade::layer::Overlays {
        polarization: true,
        ..Default::default()
    };
    let (w, h) = (900, 300);
    let layer = overlays.draw(w, h).expect("a legend");
    let legend = shade::legend::Legend::polarization(w, h, 0).unwrap();
    let b = legend.bar;
    let y = ((b.y0 + b.y1) / 2) as u32;
    let end = |x: i64| {
        let p = layer.get_pixel(x as u32, y).0;
        [p[0], p[1], p[2]]
    };
    // Both ends of the bar show the same colour (0° and 180° are one line).
    assert_eq!(end(b.x0), cyclic_colour(0.0));
    assert!((0..3).all(|i| end(b.x1 - 1)[i].abs_diff(cyclic_colour(0.0)[i]) <= 8));
    assert!(legend.title.is_some());
}

#[test]
fn bad_axes_and_files_without_the_channels_are_refused() {
    let d = data(true);
    let mut s = settings(&d, vec![ShaderKind::Texture, ShaderKind::Polarization]);
    s.objects.get_mut("ball").unwrap().polarization = Some([0.0, 0.0, 0.0]);
    let e = Shading::new(&d, &s).unwrap_err().to_string();
    assert!(e.contains("objects.ball.polarization"), "{e}");
    s.objects.get_mut("ball").unwrap().polarization = Some([f64::NAN, 0.0, 1.0]);
    let e = Shading::new(&d, &s).unwrap_err().to_string();
    assert!(e.contains("objects.ball.polarization[0]"), "{e}");
    let old = data(false);
    let s = settings(&old, vec![ShaderKind::Polarization]);
    let e = Shading::new(&old, &s).unwrap_err().to_string();
    assert!(e.contains("shaders") && e.contains("pol_x"), "{e}");
    assert_eq!(
        "polarization".parse::<ShaderKind>(),
        Ok(ShaderKind::Polarization)
    );
}
