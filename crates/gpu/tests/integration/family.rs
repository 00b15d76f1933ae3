//! The GPU kernel in the Gödel-type family against the CPU exact tracer (docs/physics.md,
//! "The GPU kernel in the family"): the example scene (an earth falling past an observer on
//! the axis, a checkered ball at rest) in every member the family's issue names,
//! m²/Ω² ∈ {−1, 0, 1, 2, 3.5, 4, 6}, and on the sphere and in the causal m² = 4Ω² an
//! off-axis observer moving at 0.6 c among a ball, a coordinate sphere and a bounded plane,
//! agree within the tolerances of single precision, the polarization channels (integrated
//! along the rays on both sides) included; and kernels with one piece of the family's physics
//! removed are caught.

use crate::common::{agreement, caught, family_member as member, scene, sized, Agreement};
use gpu::KERNEL;

/// An observer off the axis moving at 0.6 c past a ball at rest, a coordinate sphere and a
/// bounded plane below, in the member m² = `ratio`·Ω², Ω = 1/√2, seen through a pinhole.
fn moving_observer(ratio: f64) -> scene::Scene {
    scene(&format!(
        "name = \"moving-{ratio}\"\n\
         [spacetime]\nmetric = \"godel-type\"\nm2 = {:?}\nomega = 0.7071067811865476\n\
         [observer]\ntime = 3.0\nposition = {{ x = 0.4, y = -0.3, z = 0.1 }}\n\
         velocity = {{ speed = 0.6, direction = [0, 1, 0] }}\nforward = [1, 0.2, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"pinhole\"\nfov_deg = 100.0\nwidth = 64\nheight = 48\n\
         [trace]\nmax_past = 10.0\n\
         [[object]]\nname = \"ball\"\nradius = 0.15\nmotion = {{ kind = \"rest\", position = {{ x = 1.1, y = 0.3, z = 0.05 }} }}\n\
         [[object]]\nname = \"sphere\"\nframe = \"coordinates\"\nshape = \"sphere\"\ncenter = {{ x = 0.2, y = 0.9, z = 0.0 }}\nradius = 0.2\n\
         [[object]]\nname = \"floor\"\nframe = \"coordinates\"\nshape = \"plane\"\nheight = -0.4\nextent = 1.5\n",
        ratio * 0.5
    ))
}

fn agrees(scene: &scene::Scene) -> Agreement {
    let a = agreement(scene, KERNEL);
    a.assert_holds();
    a
}

#[test]
fn every_member_of_the_issue_agrees() {
    for ratio in [-1.0, 0.0, 1.0, 2.0, 3.5, 4.0, 6.0] {
        let a = agrees(&member(ratio));
        assert!(
            a.seen > 20,
            "{}: too few samples see an object: {a:?}",
            a.name
        );
    }
}

#[test]
fn a_moving_observer_off_the_axis_agrees_on_the_sphere_and_where_light_escapes() {
    for ratio in [-1.0, 4.0] {
        let a = agrees(&moving_observer(ratio));
        assert!(
            a.seen > 200,
            "{}: too few samples see an object: {a:?}",
            a.name
        );
    }
}

#[test]
fn a_kernel_without_the_members_loop_copies_is_caught() {
    caught(
        &member(1.0),
        "r.shift = vec2(e1.x - at.x, e1.w - at.w);",
        "r.shift = vec2(e1.x - at.x, 0.0);",
    );
}

#[test]
fn a_kernel_whose_balls_are_not_in_the_godel_like_chart_is_caught() {
    caught(
        &member(-1.0),
        "    return chartEvent(e);\n",
        "    return e;\n",
    );
}

#[test]
fn a_kernel_without_the_members_polarization_transport_is_caught() {
    caught(
        &moving_observer(4.0),
        "            hp.up = moved[0];\n            hp.right = moved[1];\n",
        "",
    );
}

#[test]
fn a_kernel_without_the_escape_stop_is_caught() {
    caught(
        &member(4.0),
        "if (step_ == -2) { finish(ESCAPED); return; }",
        "",
    );
}

#[test]
fn a_kernel_whose_falling_balls_take_the_mean_rates_time_guess_is_caught() {
    // On the sphere the earth hovers in t near ρ_c: the mean rate's guess is far off there.
    caught(
        &member(-2.0),
        "    if (lret < INF) {\n        // One worldline",
        "    if (false) {\n        // One worldline",
    );
}

#[test]
fn lit_members_agree_light_for_light() {
    let a = agrees(&sized(crate::common::example("lit-godel-type"), 90, 10));
    assert!(a.lit > 20, "{}: too few lit samples: {a:?}", a.name);
    // (Not m² = 4Ω²: there the CPU takes minutes for the connecting rays whose loops run far
    // out as Λ → 0; the kernel agrees with it at 64×48, every light within 10⁻³.)
    for ratio in [-1.0, 6.0] {
        let lit = format!(
            "{}[[light]]\nposition = {{ x = 0.6, y = 0.4, z = 0.5 }}\npower = 6.0\n",
            moving_observer(ratio).source_text
        );
        let a = agrees(&scene(&lit));
        assert!(a.lit > 200, "{}: too few lit samples: {a:?}", a.name);
    }
}
