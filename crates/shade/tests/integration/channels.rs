//! The channel path ([`Shading::image_into_with`] from a [`Channels`] copy) against the
//! record path ([`Shading::image_into`]): byte-identical RGB for every shader case of the
//! benchmark (and a few more settings), on synthetic data with every ray status, missing and
//! unknown objects, odd values (NaN, negative, zero shifts), one sample per pixel and 2×2.

#[path = "../../benches/common/mod.rs"]
mod common;

use datafile::record::{PixelRecord, RayStatus};
use datafile::DataFile;
use shade::{Channels, Needs, ShadeSettings, Shading};

/// The benchmark's synthetic file at `w` × `h` with every status, object −1 and an unknown
/// object, NaN and negative values sprinkled in, and odd light values.
fn varied(w: usize, h: usize) -> DataFile {
    let mut data = common::data_of(w, h);
    for (i, r) in data.records.iter_mut().enumerate() {
        match i % 23 {
            0 => r.status = RayStatus::Failed,
            1 => r.status = RayStatus::StepBudget,
            2 => r.status = RayStatus::NotTraced,
            3 => r.status = RayStatus::WorkLimit,
            4 => {
                *r = PixelRecord {
                    status: RayStatus::Escaped,
                    ..*r
                }
            }
            5 => r.object = 7, // not an object of the file
            6 => r.g = 0.0,
            7 => r.g = f32::NAN,
            8 => r.cos_i = f32::NAN,
            9 => r.cos_i = -0.5,
            10 => r.t_emit = -2.0, // inside the default time window
            11 => r.g = 40.0,      // far beyond the tone curve's knee
            _ => {}
        }
    }
    for (k, plane) in data.lights.iter_mut().enumerate() {
        for (i, x) in plane.iter_mut().enumerate() {
            match (i + k) % 17 {
                0 => *x = f32::NAN,
                1 => *x = -1.0,
                2 => *x = 30.0,
                _ => {}
            }
        }
    }
    data
}

/// The benchmark's cases, each also with exposure +2.5 stops.
fn all_cases(data: &DataFile) -> Vec<(String, ShadeSettings)> {
    let mut out = Vec::new();
    for (name, _, s) in common::cases(data) {
        let mut bright = s.clone();
        bright.ev = 2.5;
        out.push((name.to_string(), s));
        out.push((format!("{name} ev 2.5"), bright));
    }
    out
}

fn record_path(shading: &Shading, data: &DataFile) -> Vec<u8> {
    let mut bytes = Vec::new();
    shading.image_into(data, &mut bytes);
    bytes
}

fn channel_path(shading: &Shading, channels: &Channels) -> Vec<u8> {
    let mut bytes = Vec::new();
    shading.image_into_with(channels, &mut bytes);
    bytes
}

fn assert_same(data: &DataFile) {
    let all = Channels::new(data, Needs::ALL);
    for (name, settings) in all_cases(data) {
        let shading = Shading::new(data, &settings).expect("valid settings");
        let old = record_path(&shading, data);
        assert_eq!(old.len(), data.picture_size().0 * data.picture_size().1 * 3);
        let only = Channels::new(data, shading.needs());
        for (what, channels) in [("needed", &only), ("all", &all)] {
            let new = channel_path(&shading, channels);
            let first = old.iter().zip(&new).position(|(a, b)| a != b);
            assert!(
                old == new,
                "{name}, {what} channels: first differing byte {first:?} of {}",
                old.len()
            );
        }
        assert_eq!(shading.image_with(&only).as_raw(), &old, "{name}");
    }
}

#[test]
fn channel_path_is_byte_identical_to_the_record_path() {
    assert_same(&varied(96, 54));
}

#[test]
fn channel_path_is_byte_identical_for_anti_aliased_files() {
    let mut data = varied(96, 54);
    data.header.supersample = 2;
    assert_eq!(data.picture_size(), (48, 27));
    assert_same(&data);
}

/// Each copied plane matters in some case: zeroing it changes a picture, so a channel the
/// copy dropped (or mixed up) would fail the comparison above.
#[test]
fn every_copied_channel_changes_some_picture() {
    let data = varied(96, 54);
    type Edit = fn(&mut Channels);
    let edits: [(&str, Edit); 9] = [
        ("status", |c| c.status.iter_mut().for_each(|x| *x = 0)),
        ("object", |c| c.object.iter_mut().for_each(|x| *x = 0)),
        ("u", |c| c.u.iter_mut().for_each(|x| *x = 0.0)),
        ("v", |c| c.v.iter_mut().for_each(|x| *x = 0.0)),
        ("g", |c| c.g.iter_mut().for_each(|x| *x = 1.0)),
        ("t_emit", |c| c.t_emit.iter_mut().for_each(|x| *x = 0.0)),
        ("cos_i", |c| c.cos_i.iter_mut().for_each(|x| *x = 1.0)),
        ("light 0", |c| c.lights[0].iter_mut().for_each(|x| *x = 0.0)),
        ("light 1", |c| c.lights[1].iter_mut().for_each(|x| *x = 0.0)),
    ];
    let shadings: Vec<Shading> = all_cases(&data)
        .iter()
        .map(|(_, s)| Shading::new(&data, s).expect("valid settings"))
        .collect();
    for (name, edit) in edits {
        let changes = shadings.iter().any(|shading| {
            let channels = Channels::new(&data, Needs::ALL);
            let mut edited = channels.clone();
            edit(&mut edited);
            channel_path(shading, &channels) != channel_path(shading, &edited)
        });
        assert!(changes, "zeroing {name} changes no picture");
    }
}

/// Channels without one the settings read give no picture rather than a wrong one.
#[test]
fn missing_channels_give_an_empty_picture() {
    let data = varied(96, 54);
    for (name, settings) in all_cases(&data) {
        let shading = Shading::new(&data, &settings).expect("valid settings");
        let needs = shading.needs();
        let fewer = [
            Needs {
                texture_coordinates: false,
                ..needs
            },
            Needs {
                shift: false,
                ..needs
            },
            Needs {
                incidence: false,
                ..needs
            },
            Needs {
                lights: false,
                ..needs
            },
        ];
        for less in fewer.into_iter().filter(|l| *l != needs) {
            let channels = Channels::new(&data, less);
            assert!(
                channel_path(&shading, &channels).is_empty(),
                "{name}: {less:?}"
            );
        }
    }
}
