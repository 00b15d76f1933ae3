//! Tests of the per-pixel data file: exact round trips, deterministic bytes,
//! clear errors on damaged or foreign files, no panics on mutated input, and
//! atomic writes that leave nothing behind on failure.

use std::path::{Path, PathBuf};

use datafile::atomic::{write_atomically, write_atomically_via_path};
use datafile::record::{PixelRecord, RayStatus};
use datafile::{attr, DataFile, DataFileErrorKind, DataHeader, FORMAT_VERSION};
use exr::prelude::{AttributeValue, FlatSamples, Text, WritableImage};
use proptest::prelude::*;

/// SplitMix64: a small deterministic generator for test data.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// A finite f32 spread over many magnitudes and both signs.
    fn f32(&mut self) -> f32 {
        let mantissa = (self.next() % 2_000_001) as f32 / 1_000_000.0 - 1.0;
        let exponent = (self.next() % 41) as i32 - 20;
        mantissa * 2f32.powi(exponent)
    }
}

fn header(objects: usize) -> DataHeader {
    DataHeader {
        format_version: FORMAT_VERSION,
        scene_name: "static-sphere ☉".into(),
        scene_text: "name = \"static-sphere\"\n# Gödel – ρ, φ, ☀\n[spacetime]\na = 1.0\n".into(),
        camera: "pinhole fov=60° 7×3".into(),
        observer_time: 0.1 + 0.2,
        metric: "godel".into(),
        godel_a: std::f64::consts::PI * 1e-7,
        member: None,
        method: "numeric".into(),
        object_names: (0..objects).map(|k| format!("object {k} ✓")).collect(),
        supersample: 1,
    }
}

fn random_file(width: usize, height: usize, lights: usize, seed: u64) -> DataFile {
    let mut rng = Rng(seed);
    let objects = 5;
    let records: Vec<PixelRecord> = (0..width * height)
        .map(|_| {
            let object = (rng.next() % (objects as u64 + 1)) as i32 - 1;
            let status = RayStatus::ALL[(rng.next() % 5) as usize];
            PixelRecord {
                object,
                status,
                u: rng.f32(),
                v: rng.f32(),
                g: rng.f32(),
                t_emit: -rng.f32().abs(),
                x: rng.f32(),
                y: rng.f32(),
                z: rng.f32(),
                lambda: rng.f32(),
                dir: [rng.f32(), rng.f32(), rng.f32()],
                cos_i: rng.f32(),
                view: [rng.f32(), rng.f32(), rng.f32()],
                pol: [rng.f32(), rng.f32(), rng.f32()],
            }
        })
        .collect();
    // Only hits carry physical values (and only traced rays a view direction): the file
    // stores NaN for the others and reads them back as the zeros of `PixelRecord::miss`.
    let records: Vec<PixelRecord> = records
        .into_iter()
        .map(|r: PixelRecord| match r.status {
            RayStatus::Hit => r,
            RayStatus::NotTraced => PixelRecord {
                object: r.object,
                ..PixelRecord::miss(r.status)
            },
            _ => PixelRecord {
                object: r.object,
                view: r.view,
                ..PixelRecord::miss(r.status)
            },
        })
        .collect();
    let lights = (0..lights)
        .map(|_| {
            let values = records.iter().map(|r| (r.has_emission(), rng.f32()));
            values.map(|(hit, v)| if hit { v } else { 0.0 }).collect()
        })
        .collect();
    DataFile {
        header: header(objects),
        width,
        height,
        records,
        lights,
        polarization: true,
    }
}

fn temp_dir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn write_bytes(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn read_kind(path: &Path) -> DataFileErrorKind {
    match DataFile::read(path) {
        Ok(_) => panic!("{} read without error", path.display()),
        Err(e) => {
            assert_eq!(e.path, path);
            assert!(e.to_string().contains(&path.display().to_string()), "{e}");
            e.kind
        }
    }
}

/// Every size reads back as written: among them one of three blocks of `DataFile::planes`
/// (8,730 records, the last block partial) with lights, whose values must stay with their
/// records from block to block.
#[test]
fn round_trip_is_exact() {
    let dir = temp_dir();
    let sizes = [
        (7, 3, 3, 1),
        (1, 1, 0, 2),
        (3, 7, 1, 3),
        (64, 40, 2, 4),
        (97, 90, 2, 5),
    ];
    for (width, height, lights, seed) in sizes {
        let file = random_file(width, height, lights, seed);
        let path = dir.path().join(format!("{width}x{height}.exr"));
        file.write(&path).unwrap();
        let back = DataFile::read(&path).unwrap();
        assert_eq!(back, file);
    }
}

#[test]
fn round_trip_keeps_special_values() {
    let mut file = random_file(4, 2, 1, 5);
    file.records[0] = PixelRecord::miss(RayStatus::NotTraced);
    file.lights[0][0] = 0.0;
    for i in 1..=5 {
        file.records[i].status = RayStatus::Hit;
    }
    file.records[1].u = f32::MAX;
    file.records[1].v = f32::MIN_POSITIVE / 8.0; // subnormal
    file.records[1].g = -0.0;
    file.records[2].x = f32::INFINITY;
    file.records[3].object = 4;
    file.lights[0][5] = f32::NAN;
    file.header.object_names.clear();
    file.header.object_names.extend([
        "a".to_string(),
        "b".into(),
        "c".into(),
        "d".into(),
        "e".into(),
    ]);
    let back = DataFile::from_bytes(&file.to_bytes().unwrap()).unwrap();
    assert!(back.lights[0][5].is_nan());
    assert_eq!(back.records[1].g.to_bits(), (-0.0f32).to_bits());
    file.lights[0][5] = 0.0;
    let mut back = back;
    back.lights[0][5] = 0.0;
    assert_eq!(back, file);
}

#[test]
fn round_trip_without_objects() {
    let mut file = random_file(5, 5, 0, 6);
    file.header.object_names.clear();
    file.header.scene_text.clear();
    for r in &mut file.records {
        *r = PixelRecord::MISS;
    }
    let back = DataFile::from_bytes(&file.to_bytes().unwrap()).unwrap();
    assert_eq!(back, file);
    assert!(back.header.object_names.is_empty());
}

#[test]
fn output_is_deterministic() {
    let dir = temp_dir();
    let file = random_file(301, 67, 2, 7); // several blocks, parallel writer
    let (a, b) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
    file.write(&a).unwrap();
    file.write(&b).unwrap();
    let bytes = std::fs::read(&a).unwrap();
    assert_eq!(bytes, std::fs::read(&b).unwrap());
    for _ in 0..5 {
        assert_eq!(file.clone().to_bytes().unwrap(), bytes);
    }
}

#[test]
fn index_and_record_helpers() {
    let file = random_file(7, 3, 0, 8);
    assert_eq!(file.index(0, 0), 0);
    assert_eq!(file.index(6, 0), 6);
    assert_eq!(file.index(0, 1), 7);
    assert_eq!(file.index(6, 2), 20);
    assert_eq!(*file.record(2, 1), file.records[9]);
}

#[test]
fn miss_record() {
    let miss = PixelRecord::miss(RayStatus::StepBudget);
    assert_eq!(miss.object, -1);
    assert_eq!(miss.status, RayStatus::StepBudget);
    assert!(!miss.is_hit());
    assert_eq!(PixelRecord::MISS.status, RayStatus::Escaped);
    for status in RayStatus::ALL {
        assert_eq!(RayStatus::from_code(status.code()), Some(status));
    }
    assert_eq!(RayStatus::from_code(RayStatus::ALL.len() as u32), None);
}

#[test]
fn truncated_files_are_errors() {
    let dir = temp_dir();
    let bytes = random_file(9, 5, 2, 9).to_bytes().unwrap();
    let n = bytes.len();
    for cut in [0, 3, 4, 8, 20, 100, 400, n / 2, n - 100, n - 10, n - 1] {
        let path = write_bytes(dir.path(), &format!("cut{cut}.exr"), &bytes[..cut]);
        let kind = read_kind(&path);
        if cut < 4 {
            assert!(matches!(kind, DataFileErrorKind::NotExr), "{kind}");
        }
    }
}

#[test]
fn foreign_and_missing_files_are_errors() {
    let dir = temp_dir();
    let path = write_bytes(dir.path(), "text.exr", b"name = \"not an image\"\n");
    assert!(matches!(read_kind(&path), DataFileErrorKind::NotExr));
    let png = [0x89, b'P', b'N', b'G', 13, 10, 26, 10, 0, 0, 0, 13];
    let path = write_bytes(dir.path(), "png.exr", &png);
    assert!(matches!(read_kind(&path), DataFileErrorKind::NotExr));
    let path = dir.path().join("absent.exr");
    assert!(matches!(read_kind(&path), DataFileErrorKind::Io(_)));
    assert!(matches!(read_kind(dir.path()), DataFileErrorKind::Io(_)));
}

/// Writes a valid data file, lets `edit` change it through the exr crate
/// directly, and returns the path of the edited file.
fn edited(dir: &Path, name: &str, edit: impl FnOnce(&mut exr::image::FlatImage)) -> PathBuf {
    let path = dir.join(name);
    random_file(7, 3, 2, 10).write(&path).unwrap();
    let mut image = exr::prelude::read_all_flat_layers_from_file(&path).unwrap();
    edit(&mut image);
    std::fs::remove_file(&path).unwrap();
    image.write().to_file(&path).unwrap();
    path
}

fn channel<'a>(image: &'a mut exr::image::FlatImage, name: &str) -> &'a mut FlatSamples {
    let layer = &mut image.layer_data[0];
    let found = layer
        .channel_data
        .list
        .iter_mut()
        .find(|c| c.name.eq(name))
        .unwrap();
    &mut found.sample_data
}

fn set_attribute(image: &mut exr::image::FlatImage, name: &str, value: Option<AttributeValue>) {
    let other = &mut image.layer_data[0].attributes.other;
    let key = Text::from(name);
    assert!(other.contains_key(&key), "{name}");
    match value {
        Some(value) => other.insert(key, value),
        None => other.remove(&key),
    };
}

fn text(value: &str) -> Option<AttributeValue> {
    Some(AttributeValue::Text(Text::from(value)))
}

#[test]
fn an_unchanged_rewrite_reads_back() {
    let dir = temp_dir();
    let path = edited(dir.path(), "same.exr", |_| {});
    assert_eq!(DataFile::read(&path).unwrap(), random_file(7, 3, 2, 10));
}

#[test]
fn missing_channel_is_named() {
    let dir = temp_dir();
    let path = edited(dir.path(), "no_g.exr", |image| {
        image.layer_data[0]
            .channel_data
            .list
            .retain(|c| !c.name.eq("g"));
    });
    let kind = read_kind(&path);
    assert!(
        matches!(&kind, DataFileErrorKind::MissingChannel(c) if c == "g"),
        "{kind}"
    );
    assert!(kind.to_string().contains("`g`"));
}

/// Files written before the polarization channels read as they did, with `polarization` false
/// and zero `pol`, and write back without them; a file with only some of the three is damaged.
#[test]
fn files_without_polarization_channels_read_and_half_of_them_is_refused() {
    let dir = temp_dir();
    let without = |image: &mut exr::image::FlatImage| {
        let list = &mut image.layer_data[0].channel_data.list;
        list.retain(|c| !["pol_x", "pol_y", "pol_z"].iter().any(|n| c.name.eq(n)));
    };
    let path = edited(dir.path(), "old.exr", without);
    let old = DataFile::read(&path).unwrap();
    assert!(!old.polarization);
    assert!(old.records.iter().all(|r| r.pol == [0.0; 3]));
    let mut expected = random_file(7, 3, 2, 10);
    expected.polarization = false;
    expected.records.iter_mut().for_each(|r| r.pol = [0.0; 3]);
    assert_eq!(old, expected, "every other channel as written");
    let again = DataFile::from_bytes(&old.to_bytes().unwrap()).unwrap();
    assert_eq!(again, old);
    let rewritten = dir.path().join("rewritten.exr");
    old.write(&rewritten).unwrap();
    let image = exr::prelude::read_all_flat_layers_from_file(&rewritten).unwrap();
    assert!(!image.layer_data[0]
        .channel_data
        .list
        .iter()
        .any(|c| c.name.to_string().starts_with("pol_")));
    // One of the three missing: refused, naming it.
    let path = edited(dir.path(), "no_pol_y.exr", |image| {
        image.layer_data[0]
            .channel_data
            .list
            .retain(|c| !c.name.eq("pol_y"));
    });
    let kind = read_kind(&path);
    assert!(
        matches!(&kind, DataFileErrorKind::MissingChannel(c) if c == "pol_y"),
        "{kind}"
    );
    let path = edited(dir.path(), "pol_u32.exr", |image| {
        *channel(image, "pol_z") = FlatSamples::U32(vec![0; 21]);
    });
    assert!(matches!(
        read_kind(&path),
        DataFileErrorKind::ChannelType { .. }
    ));
}

#[test]
fn wrong_channel_type_is_reported() {
    let dir = temp_dir();
    let path = edited(dir.path(), "status_f32.exr", |image| {
        *channel(image, "status") = FlatSamples::F32(vec![0.0; 21]);
    });
    let kind = read_kind(&path);
    assert!(
        matches!(&kind, DataFileErrorKind::ChannelType { channel, expected: "u32", found: "f32" } if channel == "status"),
        "{kind}"
    );
    let path = edited(dir.path(), "light_u32.exr", |image| {
        *channel(image, "light_1") = FlatSamples::U32(vec![0; 21]);
    });
    assert!(matches!(
        read_kind(&path),
        DataFileErrorKind::ChannelType { .. }
    ));
}

#[test]
fn bad_values_are_reported() {
    let dir = temp_dir();
    let cases: [(&str, f32); 5] = [
        ("half", 1.5),
        ("nan", f32::NAN),
        ("minus_two", -2.0),
        ("too_big", 5.0),
        ("inf", f32::INFINITY),
    ];
    for (name, value) in cases {
        let path = edited(dir.path(), &format!("object_{name}.exr"), |image| {
            let FlatSamples::F32(values) = channel(image, "object") else {
                panic!()
            };
            values[8] = value;
        });
        let kind = read_kind(&path);
        assert!(
            matches!(
                kind,
                DataFileErrorKind::BadValue {
                    channel: "object",
                    col: 1,
                    row: 1,
                    ..
                }
            ),
            "{name}: {kind}"
        );
    }
    let path = edited(dir.path(), "status_7.exr", |image| {
        let FlatSamples::U32(values) = channel(image, "status") else {
            panic!()
        };
        values[20] = 7;
    });
    let kind = read_kind(&path);
    assert!(matches!(
        kind,
        DataFileErrorKind::BadValue {
            channel: "status",
            col: 6,
            row: 2,
            ..
        }
    ));
}

#[test]
fn bad_attributes_are_reported() {
    let dir = temp_dir();
    type Case = (&'static str, &'static str, Option<AttributeValue>);
    let cases: Vec<Case> = vec![
        ("no_scene", attr::SCENE, None),
        ("no_version", attr::FORMAT_VERSION, None),
        ("a_text", attr::A, text("one point five")),
        ("a_nan", attr::A, text("NaN")),
        ("time_empty", attr::OBSERVER_TIME, text("")),
        ("version_text", attr::FORMAT_VERSION, text("v1")),
        ("version_1", attr::FORMAT_VERSION, text("1")),
        ("supersample_0", attr::SUPERSAMPLE, text("0")),
        ("supersample_17", attr::SUPERSAMPLE, text("17")),
        ("supersample_half", attr::SUPERSAMPLE, text("1.5")),
        ("supersample_3", attr::SUPERSAMPLE, text("3")),
        ("a_float", attr::A, Some(AttributeValue::F32(1.0))),
        (
            "metric_latin1",
            attr::METRIC,
            Some(AttributeValue::Text(Text::from("g\u{f6}del"))),
        ),
        ("one_object", attr::OBJECTS, text("sphere")),
    ];
    for (file, name, value) in cases {
        let path = edited(dir.path(), &format!("{file}.exr"), |image| {
            set_attribute(image, name, value);
        });
        let kind = read_kind(&path);
        let message = kind.to_string();
        match file {
            "no_scene" | "no_version" => {
                assert!(matches!(kind, DataFileErrorKind::MissingAttribute(n) if n == name))
            }
            "version_1" => assert!(matches!(kind, DataFileErrorKind::UnsupportedVersion(1))),
            // 7×3 records are not a whole number of 3×3 sample blocks.
            "supersample_3" => {
                assert!(
                    matches!(kind, DataFileErrorKind::Inconsistent(_)),
                    "{message}"
                )
            }
            "one_object" => assert!(matches!(kind, DataFileErrorKind::BadValue { .. })),
            _ => assert!(
                matches!(kind, DataFileErrorKind::BadAttribute { name: n, .. } if n == name),
                "{file}: {message}"
            ),
        }
        assert!(!message.is_empty());
    }
}

#[test]
fn records_without_a_hit_store_nan_in_the_physical_channels() {
    let dir = temp_dir();
    let mut file = random_file(6, 2, 2, 21);
    let statuses = [RayStatus::Hit, RayStatus::Escaped, RayStatus::NotTraced];
    for (i, r) in file.records.iter_mut().enumerate() {
        let status = statuses[i % 3];
        *r = match status {
            RayStatus::Hit => PixelRecord {
                object: 1,
                status,
                ..*r
            },
            RayStatus::NotTraced => PixelRecord::miss(status), // no direction
            _ => PixelRecord {
                view: [0.6, 0.0, 0.8],
                ..PixelRecord::miss(status)
            },
        };
    }
    for plane in &mut file.lights {
        for (i, v) in plane.iter_mut().enumerate() {
            *v = if i % 3 == 0 { 0.5 } else { 0.0 };
        }
    }
    let path = dir.path().join("nan.exr");
    file.write(&path).unwrap();
    // Through the exr crate, as any analysis would read it.
    let image = exr::prelude::read_all_flat_layers_from_file(&path).unwrap();
    let layer = &image.layer_data[0];
    let plane = |name: &str| -> Vec<f32> {
        let c = layer.channel_data.list.iter().find(|c| c.name.eq(name));
        match &c.unwrap_or_else(|| panic!("no channel {name}")).sample_data {
            FlatSamples::F32(v) => v.clone(),
            _ => panic!("{name} is not f32"),
        }
    };
    let physical = [
        "u", "v", "g", "t_emit", "x", "y", "z", "lambda", "dir_x", "dir_y", "dir_z", "cos_i",
        "pol_x", "pol_y", "pol_z", "light_0", "light_1",
    ];
    for name in physical {
        for (i, v) in plane(name).iter().enumerate() {
            assert_eq!(v.is_nan(), i % 3 != 0, "{name}[{i}] = {v}");
        }
    }
    for name in ["view_x", "view_y", "view_z"] {
        for (i, v) in plane(name).iter().enumerate() {
            assert_eq!(v.is_nan(), i % 3 == 2, "{name}[{i}] = {v}");
        }
    }
    assert_eq!(plane("view_z")[1], 0.8);
    // Read back: the in-memory zeros of a miss, exactly the records written.
    assert_eq!(DataFile::read(&path).unwrap(), file);
}

/// A stretch of records without a hit (most of a scene's sky) stores the same NaN in its
/// physical channels: OpenEXR's RLE must find runs there. With a NaN whose bytes do not repeat
/// in pairs (the usual 0x7fc00000), the split into even and odd bytes leaves no run and the
/// file was as large as its raw channels.
#[test]
fn missed_pixels_compress() {
    let (width, height) = (256, 32);
    let mut file = random_file(width, height, 0, 5);
    for (i, r) in file.records.iter_mut().enumerate() {
        // One hit in sixteen, the rest escaped with a direction each.
        *r = if i % 16 == 0 {
            PixelRecord {
                object: 0,
                status: RayStatus::Hit,
                ..*r
            }
        } else {
            PixelRecord {
                view: r.view,
                ..PixelRecord::miss(RayStatus::Escaped)
            }
        };
    }
    let bytes = file.to_bytes().unwrap();
    // object, status, 12 physical, 3 view and 3 polarization channels of 4 bytes; the
    // physical and polarization ones (15 of the 20) are NaN in 15 pixels of 16.
    let raw = width * height * 20 * 4;
    assert!(
        bytes.len() * 2 < raw,
        "{} bytes for {raw} raw: the missed pixels' NaN did not compress",
        bytes.len()
    );
    assert_eq!(DataFile::from_bytes(&bytes).unwrap(), file);
}

#[test]
fn supersampled_files_name_their_factor_and_group_samples_into_pixels() {
    let mut file = random_file(6, 4, 1, 22);
    file.header.supersample = 2;
    let back = DataFile::from_bytes(&file.to_bytes().unwrap()).unwrap();
    assert_eq!(back.header.supersample, 2);
    assert_eq!(back.picture_size(), (3, 2));
    // Picture pixel (2, 1) is the samples at columns 4, 5 and rows 2, 3.
    let at: Vec<usize> = back.sample_indices(2, 1).collect();
    assert_eq!(at, vec![2 * 6 + 4, 2 * 6 + 5, 3 * 6 + 4, 3 * 6 + 5]);
    let mean = back.box_filter(2, 1, |i| [i as f32, 1.0, 0.0]);
    assert_eq!(mean, [(16 + 17 + 22 + 23) as f32 / 4.0, 1.0, 0.0]);
    // A factor that does not divide the image is refused when writing.
    file.header.supersample = 4;
    assert!(matches!(
        file.to_bytes(),
        Err(DataFileErrorKind::Inconsistent(_))
    ));
}

#[test]
fn invalid_data_is_not_written() {
    let dir = temp_dir();
    let path = dir.path().join("bad.exr");
    let mut file = random_file(4, 4, 1, 11);
    file.records.pop();
    assert!(matches!(
        file.write(&path).unwrap_err().kind,
        DataFileErrorKind::Inconsistent(_)
    ));
    let mut file = random_file(4, 4, 1, 11);
    file.lights[0].push(1.0);
    assert!(file.write(&path).is_err());
    let mut file = random_file(4, 4, 1, 11);
    file.records[3].object = 5; // only 5 objects
    assert!(matches!(
        file.write(&path).unwrap_err().kind,
        DataFileErrorKind::BadValue { .. }
    ));
    let mut file = random_file(4, 4, 1, 11);
    file.header.object_names[2] = "two\nlines".into();
    assert!(file.write(&path).is_err());
    let mut file = random_file(4, 4, 1, 11);
    file.header.observer_time = f64::NAN;
    assert!(file.write(&path).is_err());
    let mut file = random_file(0, 4, 1, 11);
    file.lights.clear();
    assert!(file.write(&path).is_err());
    assert!(!path.exists());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "temporary files left"
    );
}

#[test]
fn failed_write_leaves_no_file() {
    let dir = temp_dir();
    let file = random_file(3, 3, 1, 12);
    // Target is a directory.
    let target = dir.path().join("taken");
    std::fs::create_dir(&target).unwrap();
    let err = file.write(&target).unwrap_err();
    assert!(matches!(err.kind, DataFileErrorKind::Io(_)), "{err}");
    assert!(target.is_dir());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "temporary files left"
    );
    // Target directory does not exist.
    let target = dir.path().join("absent").join("x.exr");
    assert!(file.write(&target).is_err());
    assert!(!target.exists());
    // Target directory is read-only (root ignores permissions: skip then).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let ro = dir.path().join("ro");
        std::fs::create_dir(&ro).unwrap();
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
        if std::fs::write(ro.join("probe"), b"").is_err() {
            let target = ro.join("x.exr");
            assert!(file.write(&target).is_err());
            assert_eq!(std::fs::read_dir(&ro).unwrap().count(), 0);
        }
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
}

#[test]
fn atomic_write_replaces_only_on_success() {
    let dir = temp_dir();
    let path = dir.path().join("out.png");
    write_atomically(&path, |f| std::io::Write::write_all(f, b"first")).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"first");
    let failed = write_atomically(&path, |f| {
        std::io::Write::write_all(f, b"partial")?;
        Err(std::io::Error::other("disk on fire"))
    });
    assert_eq!(failed.unwrap_err().to_string(), "disk on fire");
    assert_eq!(std::fs::read(&path).unwrap(), b"first");
    write_atomically_via_path(&path, |temp| std::fs::write(temp, b"second")).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"second");
    let failed = write_atomically_via_path(&dir.path().join("never"), |temp| {
        std::fs::write(temp, b"x")?;
        Err(std::io::Error::other("no"))
    });
    assert!(failed.is_err());
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["out.png"]);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&path).unwrap().permissions().mode();
        assert_ne!(mode & 0o044, 0, "output should not be private: {mode:o}");
    }
}

fn small_valid_bytes() -> Vec<u8> {
    random_file(5, 3, 1, 14).to_bytes().unwrap()
}

#[derive(Clone, Debug)]
enum Mutation {
    Flip { at: usize, bits: u8 },
    Set { at: usize, byte: u8 },
    Truncate { at: usize },
    Insert { at: usize, bytes: Vec<u8> },
    Remove { at: usize, len: usize },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = 0usize..4096;
    prop_oneof![
        (at.clone(), 1u8..=255).prop_map(|(at, bits)| Mutation::Flip { at, bits }),
        (at.clone(), any::<u8>()).prop_map(|(at, byte)| Mutation::Set { at, byte }),
        at.clone().prop_map(|at| Mutation::Truncate { at }),
        (at.clone(), prop::collection::vec(any::<u8>(), 1..16))
            .prop_map(|(at, bytes)| Mutation::Insert { at, bytes }),
        (at, 1usize..16).prop_map(|(at, len)| Mutation::Remove { at, len }),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let n = bytes.len();
    match m {
        Mutation::Flip { at, bits } => bytes[at % n] ^= bits,
        Mutation::Set { at, byte } => bytes[at % n] = *byte,
        Mutation::Truncate { at } => bytes.truncate(at % n),
        Mutation::Insert { at, bytes: new } => {
            let at = at % (n + 1);
            bytes.splice(at..at, new.iter().copied());
        }
        Mutation::Remove { at, len } => {
            let at = at % n;
            bytes.drain(at..(at + len).min(n));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn mutated_files_never_panic(mutations in prop::collection::vec(mutation(), 1..4)) {
        let mut bytes = small_valid_bytes();
        for m in &mutations {
            if bytes.is_empty() {
                break;
            }
            apply(&mut bytes, m);
        }
        // Ok (a flip in an unused byte) or Err, never a panic.
        if let Ok(file) = DataFile::from_bytes(&bytes) {
            prop_assert_eq!(file.records.len(), file.width * file.height);
        }
    }
}
