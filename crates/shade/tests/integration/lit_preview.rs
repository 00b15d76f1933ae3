//! The lit preview: texture × (ambient + Σ colour_k · light_k), and the light sum any shader
//! can reuse.

use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;
use shade::colour::display_srgb8;
use shade::texture_shader::{direct_light, shade_lit, LIT_AMBIENT};
use shade::Texture;

fn data(lights: Vec<Vec<f32>>) -> DataFile {
    let hit = PixelRecord {
        object: 0,
        status: RayStatus::Hit,
        g: 1.0,
        ..PixelRecord::MISS
    };
    DataFile {
        header: testkit::godel_header("lit", "", "test", &["ball"]),
        width: 4,
        height: 1,
        records: vec![hit, hit, hit, PixelRecord::MISS],
        lights,
        polarization: false,
    }
}

#[test]
fn direct_light_sums_coloured_planes_and_ignores_bad_values() {
    let d = data(vec![
        vec![0.5, 0.0, f32::NAN, 0.0],
        vec![0.25, 0.1, -3.0, 0.0],
    ]);
    let colours = [[1.0, 0.5, 0.0], [0.0, 1.0, 1.0]];
    assert_eq!(direct_light(&d, 0, &colours), [0.5, 0.5, 0.25]);
    assert_eq!(direct_light(&d, 1, &colours), [0.0, 0.1, 0.1]);
    // NaN and negative light add nothing.
    assert_eq!(direct_light(&d, 2, &colours), [0.0, 0.0, 0.0]);
    // A missing plane or index adds nothing either.
    assert_eq!(direct_light(&d, 99, &colours), [0.0, 0.0, 0.0]);
}

#[test]
fn lit_preview_multiplies_the_texture_by_ambient_plus_light() {
    let d = data(vec![vec![0.5, 0.0, 2.0, 7.0]]);
    let tex = [Texture::Uniform([0.8, 0.4, 0.2])];
    let img = shade_lit(&d, &tex, &[[1.0, 1.0, 1.0]], [0.0, 0.0, 1.0]);
    let px = |c| img.get_pixel(c, 0).0;
    // Hit pixels as displayed: through the tone curve (2.06 × 0.8 is above its knee).
    let want = |l: f32| display_srgb8([0.8, 0.4, 0.2].map(|c| c * (LIT_AMBIENT + l)), 1.0);
    assert_eq!(px(0), want(0.5));
    assert_eq!(px(1), want(0.0));
    assert_eq!(px(2), want(2.0));
    // A miss shows the background, whatever its light value.
    assert_eq!(px(3), [0, 0, 255]);
    assert!(px(0)[0] > px(1)[0]);
}

#[test]
fn the_preview_of_a_scene_with_lights_is_lit() {
    let text = "name = \"lit\"\n[camera]\nkind = \"pinhole\"\nfov_deg = 60.0\nwidth = 4\nheight = 1\n[[object]]\nname = \"ball\"\nradius = 0.2\ntexture = { kind = \"uniform\", color = [0.8, 0.4, 0.2] }\nmotion = { kind = \"rest\", position = { r = 1.0, phi = 0.0, z = 0.0 } }\n";
    let unlit = scene::Scene::from_str(text, "unlit.toml").unwrap();
    let lit = scene::Scene::from_str(
        &format!("{text}[[light]]\nposition = {{ r = 1.5, phi = 0.0, z = 0.0 }}\ncolor = [1.0, 1.0, 1.0]\n"),
        "lit.toml",
    )
    .unwrap();
    let tex = [Texture::Uniform([0.8, 0.4, 0.2])];
    let d = data(vec![vec![0.5, 0.0, 2.0, 7.0]]);
    let a = shade::texture_shader::preview_with_textures(&d, &tex, &lit);
    assert_eq!(
        a,
        shade_lit(&d, &tex, &[[1.0, 1.0, 1.0]], shade::BACKGROUND)
    );
    let b = shade::texture_shader::preview_with_textures(&d, &tex, &unlit);
    assert_eq!(b, shade::shade_textures(&d, &tex, shade::BACKGROUND));
    assert_ne!(a, b);
}
