//! The GPU kernel against the CPU exact tracer (docs/physics.md, "The GPU kernel"): every
//! example scene and the hard cases (an observer inside a sphere, an off-axis observer moving
//! at 0.9 c, a = 0.5 and a = 2, 28 images of a falling ball, lit scenes) agree within the
//! tolerances of single precision, the polarization channels included; and kernels with one
//! piece of the physics removed (the loop copies, the isometry, the boost, the free fall, the
//! occlusion, the polarization's parallel transport) are caught.
//!
//! The kernel runs in an offscreen OpenGL ES 3 context: on this machine Mesa's llvmpipe, which
//! the test command installs.

use crate::common::{self, agreement, caught, example, scene, sized, Agreement};
use gpu::KERNEL;

/// The agreement of the real kernel on `scene`, asserted.
fn agrees(scene: &scene::Scene) -> Agreement {
    let a = agreement(scene, KERNEL);
    a.assert_holds();
    a
}

#[test]
fn the_static_examples_agree() {
    for (name, w, h) in [
        ("static-sphere", 440, 50),
        ("static-sphere-checker", 440, 50),
        ("static-sphere-closeup", 40, 30),
        ("beyond-horizon", 220, 25),
        ("bench-static", 220, 25),
        ("look-around", 128, 64),
        ("fly-through", 220, 25),
    ] {
        agrees(&sized(example(name), w, h));
    }
}

#[test]
fn the_falling_ball_of_the_reference_scene_agrees() {
    agrees(&sized(example("reference"), 220, 25));
}

/// The scene of 28 images of a falling ball, its rays followed 300a into the past (each
/// image in a later loop copy of its rays), in the band of its panorama where they are.
fn twenty_eight_images() -> scene::Scene {
    let mut s = example("moving-sphere-long");
    s.camera = scene::Camera::Panorama {
        h_fov_deg: 220.0,
        v_fov_deg: 3.0,
        width: 880,
        height: 12,
    };
    s
}

#[test]
fn twenty_eight_images_of_a_falling_ball_agree() {
    let a = agrees(&twenty_eight_images());
    assert!(a.seen > 100, "{a:?}");
}

#[test]
fn the_lit_examples_agree() {
    for name in ["lit-side", "lit-shadow", "lit-beyond-horizon"] {
        let a = agrees(&sized(example(name), 360, 40));
        assert!(a.lit > 100, "{name}: too few lit samples compared: {a:?}");
    }
}

#[test]
fn the_floor_grid_with_its_light_agrees() {
    let a = agrees(&sized(example("floor-grid"), 128, 72));
    assert!(a.lit > 1000, "{a:?}");
    // Few hit events move in single precision: rays grazing the floor after many loops.
    assert!(a.lit_moved * 100 < a.lit, "{a:?}");
}

/// Two floors a fiftieth of a apart, `first` listed first: a ray down crosses both within
/// one segment, and the floor listed second is searched only up to the first one's crossing
/// (where its height is the line's through the segment's ends: a plane's f is linear).
fn two_floors(first: f64, second: f64) -> scene::Scene {
    let floor = |name: &str, height: f64| {
        format!(
            "[[object]]\nname = \"{name}\"\nframe = \"coordinates\"\nshape = \"plane\"\n\
             height = {height}\nextent = 3.0\ntexture = {{ kind = \"checker\", rows = 12, cols = 12 }}\n"
        )
    };
    let text = format!(
        "name = \"two floors\"\n[spacetime]\nmetric = \"godel\"\na = 1.0\n\
         [observer]\ntime = 0.0\nposition = {{ r = 0.3, phi = 0.5, z = 0.0 }}\n\
         forward = [0.8, 0.0, -0.6]\nup = [0.6, 0.0, 0.8]\n\
         [camera]\nkind = \"pinhole\"\nfov_deg = 90.0\nwidth = 64\nheight = 36\n\
         [trace]\nmethod = \"exact\"\nmax_past = 30.0\n{}{}",
        floor("first", first),
        floor("second", second)
    );
    scene(&text)
}

#[test]
fn two_floors_close_together_agree() {
    for (first, second) in [(-0.5, -0.52), (-0.52, -0.5)] {
        let a = agrees(&two_floors(first, second));
        assert!(a.seen > 1000, "{first}, {second}: {a:?}");
    }
}

#[test]
fn an_observer_inside_spheres_sees_their_inner_surfaces_alike() {
    // The surroundings (a coordinate sphere around the observer), and a local ball at rest
    // with the observer inside it.
    agrees(&sized(example("surroundings"), 180, 40));
    agrees(&scene(&testkit::axis_panorama(
        "inside-ball",
        180,
        20,
        10.0,
        &testkit::ball_at_rest("around", 0.3, 0.1, 0.5),
    )));
}

/// An observer off the axis at (r, φ) = (0.8, 1.2), moving at 0.9 c, looking at two balls at
/// rest and a falling one.
fn off_axis_fast_observer() -> scene::Scene {
    scene(
        "name = \"off-axis\"\n\
         [spacetime]\nmetric = \"godel\"\na = 1.0\n\
         [observer]\ntime = 3.0\nposition = { r = 0.8, phi = 1.2, z = 0.1 }\n\
         velocity = { speed = 0.9, direction = [0.3, -1, 0.2] }\n\
         forward = [1, 0, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"panorama\"\nh_fov_deg = 360.0\nv_fov_deg = 60.0\nwidth = 240\nheight = 40\n\
         [trace]\nmax_past = 20.0\n\
         [[object]]\nname = \"a\"\nradius = 0.2\nmotion = { kind = \"rest\", position = { r = 0.4, phi = 0.0, z = 0.0 } }\n\
         [[object]]\nname = \"b\"\nradius = 0.15\nmotion = { kind = \"rest\", position = { r = 1.4, phi = 2.5, z = 0.2 } }\n\
         [[object]]\nname = \"c\"\nradius = 0.1\nmotion = { kind = \"geodesic\", time = 0.0, position = { x = -0.5, y = 0.5, z = 0.0 }, speed = 0.6, direction = [1, 0, 0.3] }\n",
    )
}

#[test]
fn an_off_axis_observer_moving_at_nine_tenths_of_c_agrees() {
    agrees(&off_axis_fast_observer());
}

/// Balls at rest at r = a/2 and 1.5a and a falling one in a universe with parameter `a`.
fn scaled(a: f64) -> scene::Scene {
    scene(&format!(
        "name = \"a-{a}\"\n\
         [spacetime]\nmetric = \"godel\"\na = {a:?}\n\
         [observer]\ntime = 0.0\nposition = {{ r = 0.0, phi = 0.0, z = 0.0 }}\nforward = [1, 0, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"panorama\"\nh_fov_deg = 360.0\nv_fov_deg = 40.0\nwidth = 240\nheight = 30\n\
         [trace]\nmax_past = {:?}\n\
         [[object]]\nname = \"near\"\nradius = {:?}\nmotion = {{ kind = \"rest\", position = {{ r = {:?}, phi = 0.5, z = 0.0 }} }}\n\
         [[object]]\nname = \"far\"\nradius = {:?}\nmotion = {{ kind = \"rest\", position = {{ r = {:?}, phi = 3.0, z = 0.0 }} }}\n\
         [[object]]\nname = \"falling\"\nradius = {:?}\nmotion = {{ kind = \"geodesic\", time = 0.0, position = {{ x = {:?}, y = 0.0, z = 0.0 }}, speed = 0.7, direction = [0, 1, 0] }}\n",
        15.0 * a,
        0.2 * a,
        0.5 * a,
        0.15 * a,
        1.5 * a,
        0.15 * a,
        -a
    ))
}

#[test]
fn universes_with_a_half_and_a_two_agree() {
    agrees(&scaled(0.5));
    agrees(&scaled(2.0));
}

#[test]
fn a_fisheye_dome_agrees_also_outside_its_circle() {
    let mut s = example("static-sphere");
    s.camera = scene::Camera::Fisheye {
        fov_deg: 180.0,
        size: 96,
    };
    s.observer.forward = [0.0, 0.0, 1.0];
    s.observer.up = [1.0, 0.0, 0.0];
    let a = agrees(&s);
    assert!(a.statuses_equal, "{a:?}");
}

#[test]
fn minkowski_rays_are_straight_on_both() {
    agrees(&scene(common::MINKOWSKI_TWO_BALLS));
}

// Mutations: each kernel below lacks one piece of the physics, and must be caught.

#[test]
fn a_kernel_without_loop_copies_is_caught() {
    caught(
        &twenty_eight_images(),
        "    ev.x += float(j) * r.shift.x;\n    ev.w += float(j) * r.shift.y;",
        "",
    );
}

#[test]
fn a_kernel_without_the_observers_isometry_is_caught() {
    caught(
        &off_axis_fast_observer(),
        "Ray r = makeRay(obs, k, observerToOrigin());",
        "Ray r = makeRay(obs, k, NO_ISO);",
    );
}

#[test]
fn a_kernel_without_the_observers_boost_is_caught() {
    caught(
        &off_axis_fast_observer(),
        "mat4 frame = boostFrame(u_obs_static, u_velocity.x, u_velocity.yzw);\n    vec4 k = frame",
        "mat4 frame = u_obs_static;\n    vec4 k = frame",
    );
}

#[test]
fn a_kernel_whose_falling_balls_stand_still_is_caught() {
    caught(
        &sized(example("reference"), 220, 25),
        "    } else if (!godel()) {\n        p.ev = objs[i].start + tau * objs[i].u0;",
        "    } else if (true) {\n        p.ev = objs[i].start + vec4(tau, 0.0, 0.0, 0.0);",
    );
}

#[test]
fn a_kernel_without_occlusion_is_caught() {
    caught(
        &sized(example("lit-shadow"), 360, 40),
        "    if (!any) return 1;",
        "    return 1;",
    );
}

#[test]
fn a_kernel_without_the_polarization_transport_is_caught() {
    // The screen vectors carried by the isometries alone, not transported along the ray: the
    // moving off-axis observer and its falling ball.
    caught(
        &off_axis_fast_observer(),
        "    legs = pushLegs(r.back, e0, transportLegs(r.geo, lambda, e0, legs, 2), 2);",
        "    legs = pushLegs(r.back, e0, legs, 2);",
    );
}
