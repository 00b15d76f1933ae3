//! The cameras of the views that `look` is compared with direct renders through, shared by
//! the tests (`look.rs`) and the example that measures the errors (`examples/look_error.rs`).

use scene::Camera;

/// A 60° pinhole, 240×160.
pub const PINHOLE: Camera = Camera::Pinhole {
    fov_deg: 60.0,
    width: 240,
    height: 160,
};

/// A 360°×60° panorama, 720×120.
pub const PANORAMA: Camera = Camera::Panorama {
    h_fov_deg: 360.0,
    v_fov_deg: 60.0,
    width: 720,
    height: 120,
};

/// A 180° dome fisheye, 240×240.
pub const FISHEYE: Camera = Camera::Fisheye {
    fov_deg: 180.0,
    size: 240,
};
