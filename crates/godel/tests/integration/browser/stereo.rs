//! The page's Stereo panel (issue 37): `godel view NAME.left.exr` of a rendered stereo pair
//! shows the panel with the pair's layout chosen and a picture of both eyes in it, the
//! picture `shade::stereo::compose` makes of each eye's data file shaded alone with the
//! page's settings; choosing the anaglyph shows that picture instead, of one eye's size.

use crate::browser_support::*;
use datafile::DataFile;
use image::RgbImage;
use scene::Layout;
use shade::{ShadeSettings, Shading};

/// Both eyes' data files shaded with the settings the page saved in `out/NAME.json`, in
/// `layout`; and the picture the page showed, `out/NAME.png`.
fn pictures(
    out: &std::path::Path,
    name: &str,
    eyes: &[DataFile; 2],
    layout: Layout,
) -> (RgbImage, RgbImage) {
    let meta: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join(format!("{name}.json"))).unwrap()).unwrap();
    let settings: ShadeSettings = serde_json::from_value(meta["settings"].clone()).unwrap();
    let [l, r] = eyes
        .each_ref()
        .map(|d| Shading::new(d, &settings).unwrap().image(d));
    let shown = image::open(out.join(format!("{name}.png")))
        .unwrap()
        .to_rgb8();
    assert_eq!(
        (
            meta["width"].as_u64().unwrap(),
            meta["height"].as_u64().unwrap()
        ),
        (u64::from(shown.width()), u64::from(shown.height()))
    );
    (shown, shade::stereo::compose(layout, &l, &r))
}

#[test]
fn the_stereo_panel_shows_both_eyes_in_the_layout_and_an_anaglyph_on_request() {
    require_browser_tools();
    let dir = tempfile::tempdir().unwrap();
    let camera = format!(
        "{}stereo = {{ separation = 0.3 }}\n",
        testkit::pinhole(60.0, 64, 32)
    );
    let text = testkit::ball_ahead("pair", &camera, "ball", &testkit::checker(8, 16));
    render(dir.path(), "pair", &text);
    let (left, right) = (
        dir.path().join("pair.left.exr"),
        dir.path().join("pair.right.exr"),
    );
    let eyes = [
        DataFile::read(&left).unwrap(),
        DataFile::read(&right).unwrap(),
    ];

    let (server, url) = start_viewer(&left, dir.path());
    let out = dir.path().join("browser");
    std::fs::create_dir(&out).unwrap();
    let seen = run_script("stereo.mjs", &url, &out, &[]);
    drop(server);
    assert_eq!(seen["console_errors"], serde_json::json!([]));
    assert_eq!(seen["error"], serde_json::Value::Null);
    assert_only_local_requests(&seen, &url);
    assert_eq!(seen["panel_shown"], true);
    assert_eq!(seen["layout_selected"], "side-by-side");

    let (pair, want) = pictures(&out, "pair", &eyes, Layout::SideBySide);
    assert_eq!(pair.dimensions(), (128, 32));
    assert!(
        pair == want,
        "the side-by-side picture is not both eyes shaded alone"
    );
    let (anaglyph, want) = pictures(&out, "anaglyph", &eyes, Layout::Anaglyph);
    assert_eq!(anaglyph.dimensions(), (64, 32));
    assert!(anaglyph == want, "the anaglyph is not both eyes' anaglyph");
    let (l, r) = (
        Shading::new(&eyes[0], &ShadeSettings::defaults_for(&eyes[0]))
            .unwrap()
            .image(&eyes[0]),
        Shading::new(&eyes[1], &ShadeSettings::defaults_for(&eyes[1]))
            .unwrap()
            .image(&eyes[1]),
    );
    assert!(l != r, "the eyes see differently");
}
