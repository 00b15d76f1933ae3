//! Where image textures may come from ([`shade::TextureSource`]) and the caps on reading them:
//! the viewer's source reads only regular files inside its folders and says the same about
//! every refused path; the command line's source reads any file the user names; both refuse
//! FIFOs (without blocking), oversized files and oversized images.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;
use shade::{
    ImageTexture, ShadeError, ShadeSettings, ShaderKind, Shading, TextureChoice, TextureSource,
    MAX_IMAGE_FILE_BYTES, MAX_IMAGE_SIDE,
};

/// A 4×2 image with distinct pixels; returns its path.
fn write_png(dir: &Path, name: &str, seed: u8) -> PathBuf {
    let img = image::RgbImage::from_fn(4, 2, |x, y| {
        image::Rgb([seed, (x * 60) as u8, (y * 120) as u8])
    });
    let path = dir.join(name);
    img.save(&path).unwrap();
    path
}

fn refused(result: Result<ImageTexture, ShadeError>) -> String {
    match result {
        Err(e @ ShadeError::ImageRefused { .. }) => e.to_string(),
        other => panic!("expected a refusal, got {other:?}"),
    }
}

/// Runs `job` on a thread; panics if it has not finished within a minute (a deadline against
/// hanging forever, not a speed check).
fn finishes<T: Send + 'static>(job: impl FnOnce() -> T + Send + 'static) -> T {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(job());
    });
    receive
        .recv_timeout(Duration::from_secs(60))
        .expect("reading the texture blocked")
}

fn mkfifo(path: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .unwrap();
    assert!(ok.success());
}

#[test]
fn within_reads_files_inside_its_folders_only() {
    let allowed = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    let inside = write_png(allowed.path(), "map.png", 10);
    std::fs::create_dir(allowed.path().join("sub")).unwrap();
    write_png(&allowed.path().join("sub"), "deep.png", 20);
    let outside = write_png(elsewhere.path(), "secret.png", 30);
    let source = TextureSource::within(&[allowed.path()]).unwrap();

    // Inside, by a relative or an absolute path: the same pixels as reading the file directly.
    let want = ImageTexture::from_file(&inside).unwrap();
    assert_eq!(source.image(Path::new("map.png")).unwrap(), want);
    assert_eq!(source.image(&inside).unwrap(), want);
    assert!(source.image(Path::new("sub/../sub/deep.png")).is_ok());

    // Outside: an existing image, a missing one, a way out through `..`, a symbolic link out
    // of the folder, a folder, and a FIFO inside: all refused with the same words.
    std::os::unix::fs::symlink(&outside, allowed.path().join("link.png")).unwrap();
    mkfifo(&allowed.path().join("pipe.png"));
    let escape = format!(
        "../{}/secret.png",
        elsewhere.path().file_name().unwrap().to_str().unwrap()
    );
    let missing = elsewhere.path().join("missing.png");
    let cases: Vec<PathBuf> = vec![
        outside.clone(),
        missing.clone(),
        PathBuf::from(&escape),
        PathBuf::from("link.png"),
        PathBuf::from("sub"),
        PathBuf::from("pipe.png"),
        PathBuf::from("/dev/zero"),
    ];
    for path in cases {
        let s = source.clone();
        let p = path.clone();
        let message = refused(finishes(move || s.image(&p)));
        // The message names the path as given and nothing else: it is the same text for a
        // file that exists and one that does not.
        let generic = message.replace(&path.display().to_string(), "P");
        assert_eq!(
            generic,
            "image texture P: no image file of that name in the folders textures may come from",
            "{path:?}"
        );
    }
}

#[test]
fn a_folder_that_is_not_one_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_png(dir.path(), "f.png", 1);
    for bad in [file.clone(), dir.path().join("nope")] {
        let e = TextureSource::within(&[&bad]).unwrap_err();
        assert!(matches!(e, ShadeError::TextureFolder { .. }), "{e:?}");
        assert!(e.to_string().contains(&bad.display().to_string()), "{e}");
    }
}

#[test]
fn fifos_are_refused_without_blocking_on_the_command_line_too() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.png");
    mkfifo(&fifo);
    let f = fifo.clone();
    let result = finishes(move || TextureSource::any().image(&f));
    match result {
        Err(e @ ShadeError::ImageNotFile { .. }) => {
            assert!(e.to_string().contains("not a regular file"), "{e}");
            assert!(e.to_string().contains("pipe.png"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    let result = finishes(|| ImageTexture::from_file(Path::new("/dev/zero")));
    assert!(
        matches!(result, Err(ShadeError::ImageNotFile { .. })),
        "{result:?}"
    );
}

#[test]
fn oversized_files_and_images_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    // A sparse file one byte over the cap: refused from its size, before reading.
    let big = dir.path().join("big.png");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(MAX_IMAGE_FILE_BYTES + 1)
        .unwrap();
    let e = ImageTexture::from_file(&big).unwrap_err();
    assert!(matches!(e, ShadeError::ImageTooLarge { .. }), "{e:?}");
    assert!(e.to_string().contains("256 MiB"), "{e}");

    // A small PNG file holding an image one pixel wider than the side cap.
    let wide = dir.path().join("wide.png");
    image::GrayImage::new(MAX_IMAGE_SIDE + 1, 1)
        .save(&wide)
        .unwrap();
    assert!(std::fs::metadata(&wide).unwrap().len() < 100_000);
    let e = ImageTexture::from_file(&wide).unwrap_err();
    assert!(matches!(e, ShadeError::ImageTooLarge { .. }), "{e:?}");
    assert!(e.to_string().contains("16384 pixels on a side"), "{e}");
    // At the cap it is read.
    let edge = dir.path().join("edge.png");
    image::GrayImage::new(MAX_IMAGE_SIDE, 1)
        .save(&edge)
        .unwrap();
    assert_eq!(ImageTexture::from_file(&edge).unwrap().width(), 16384);
}

/// A scene whose one object wears the image at the path TEXTURE.
fn scene() -> String {
    format!(
        "name = \"tex\"\n{}{}",
        testkit::pinhole(90.0, 2, 1),
        r#"[[object]]
name = "ball"
radius = 0.1
texture = { kind = "image", path = "TEXTURE" }
motion = { kind = "rest", position = { r = 1.0, phi = 0.0, z = 0.0 } }
"#
    )
}

/// A 2×1 data file whose embedded scene maps the image `texture` onto its one object;
/// pixel 0 hits it, pixel 1 misses.
fn data(texture: &str) -> DataFile {
    DataFile {
        header: testkit::godel_header(
            "tex",
            &scene().replace("TEXTURE", texture),
            "pinhole",
            &["ball"],
        ),
        width: 2,
        height: 1,
        records: vec![
            PixelRecord {
                object: 0,
                status: RayStatus::Hit,
                u: 0.3,
                v: 0.7,
                cos_i: 1.0,
                view: [0.0; 3],
                ..PixelRecord::MISS
            },
            PixelRecord::MISS,
        ],
        lights: Vec::new(),
        polarization: false,
    }
}

#[test]
fn settings_name_image_files_through_the_source() {
    let allowed = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    let inside = write_png(allowed.path(), "inside.png", 200);
    let outside = write_png(elsewhere.path(), "outside.png", 100);
    let data = data(inside.to_str().unwrap());
    let source = TextureSource::within(&[allowed.path()]).unwrap();
    let settings = |path: &Path| {
        let mut s = ShadeSettings::defaults_for(&data);
        s.shaders = vec![ShaderKind::Texture];
        s.objects.get_mut("ball").unwrap().texture = TextureChoice::Image {
            path: path.to_path_buf(),
        };
        s
    };
    // The command line reads any file it is given; the viewer's source refuses the outside one.
    let cli = Shading::new(&data, &settings(&outside)).unwrap();
    let e = Shading::with_textures(&data, &settings(&outside), &source).unwrap_err();
    assert!(matches!(e, ShadeError::ImageRefused { .. }), "{e:?}");
    // Inside, relative to the folder, it shades as the command line does from the full path.
    let viewer = Shading::with_textures(&data, &settings(Path::new("inside.png")), &source)
        .unwrap()
        .pixel(&data, 0);
    let want = Shading::new(&data, &settings(&inside))
        .unwrap()
        .pixel(&data, 0);
    assert_eq!(viewer, want);
    assert_ne!(cli.pixel(&data, 0), want, "the two images differ");
}

#[test]
fn the_embedded_scenes_textures_resolve_in_the_folders_and_load_once() {
    let first = tempfile::tempdir().unwrap();
    let second = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    write_png(second.path(), "only-in-second.png", 50);
    let outside = write_png(elsewhere.path(), "outside.png", 60);
    let source = TextureSource::within(&[first.path(), second.path()]).unwrap();

    // A relative path found in the second folder.
    let d = data("only-in-second.png");
    let textures = source.scene_textures(&d).unwrap();
    let want = ImageTexture::from_file(&second.path().join("only-in-second.png")).unwrap();
    assert_eq!(textures, vec![shade::Texture::Image(want.clone())]);

    // An absolute path outside every folder: refused, though the file exists.
    let e = source
        .scene_textures(&data(outside.to_str().unwrap()))
        .unwrap_err();
    assert!(matches!(e, ShadeError::ImageRefused { .. }), "{e:?}");

    // Loaded once: after the file is gone, preparing settings for that data file still works,
    // and a source without the preloaded textures now fails.
    let loaded = source.clone().with_scene_textures(&d).unwrap();
    std::fs::remove_file(second.path().join("only-in-second.png")).unwrap();
    let defaults = ShadeSettings::defaults_for(&d);
    let shading = Shading::with_textures(&d, &defaults, &loaded).unwrap();
    let c = shading.pixel(&d, 0);
    assert!(c.iter().any(|&x| x > 0.0), "{c:?}");
    assert!(Shading::with_textures(&d, &defaults, &source).is_err());
    assert_eq!(
        loaded.scene_textures(&d).unwrap(),
        vec![shade::Texture::Image(want)]
    );
}
