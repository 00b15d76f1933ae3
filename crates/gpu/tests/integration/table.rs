//! The scene table the packer writes (crates/gpu/src/input.rs) is the one the kernel reads
//! (docs/physics.md, "The GPU kernel"): both sides have the same layout constants, the table
//! does not depend on the observer (the page flies many observers with one table), the
//! Christoffel symbols it leaves out vanish, and balls
//! at rest and in free fall, whose frames, Christoffel symbols, closed forms and isometries the
//! packer computes, are traced as the CPU traces them also late in time, where the start's
//! time enters only relative to the observer's. The observer's uniforms that the packer makes
//! (its static frame and isometry to the origin) are `spacetime`'s.
//!
//! The kernel runs in an offscreen OpenGL ES 3 context (Mesa's llvmpipe here).

use crate::common::{agreement, off_axis_lit_floor, scene, MINKOWSKI_TWO_BALLS};
use gpu::input::{KernelInput, LIGHT_TEXELS, OBJECT_TEXELS, TABLE_WIDTH};
use gpu::KERNEL;
use scene::Motion;
use spacetime::{Event, Godel, Isometry, LocalVelocity, Metric, Minkowski, Spacetime};

/// The value of the kernel's `const int NAME = value;`.
fn kernel_constant(name: &str) -> usize {
    let declaration = format!("const int {name} = ");
    let at = KERNEL
        .find(&declaration)
        .unwrap_or_else(|| panic!("the kernel declares no {name}"))
        + declaration.len();
    let value = &KERNEL[at..at + KERNEL[at..].find(';').expect("a declaration ends")];
    value.trim().parse().expect("an integer")
}

#[test]
fn the_kernel_reads_the_layout_the_packer_writes() {
    for (name, packer) in [
        ("TABLE_WIDTH", TABLE_WIDTH),
        ("OBJECT_TEXELS", OBJECT_TEXELS),
        ("LIGHT_TEXELS", LIGHT_TEXELS),
    ] {
        assert_eq!(kernel_constant(name), packer, "{name}");
    }
}

#[test]
fn christoffel_symbols_with_a_z_index_vanish_as_the_table_assumes() {
    // The table keeps a ball at rest's Γ^μ_αβ for μ, α, β in t, x, y only.
    for metric in [Metric::Godel(Godel::new(0.7)), Metric::Minkowski(Minkowski)] {
        for (x, y, z) in [(0.0, 0.0, 0.0), (0.9, -0.4, 2.0), (-3.0, 5.0, -1.0)] {
            let g = metric.christoffel(Event::new(1.5, x, y, z));
            for (mu, a, b) in
                (0..4).flat_map(|m| (0..4).flat_map(move |a| (0..4).map(move |b| (m, a, b))))
            {
                if mu == 3 || a == 3 || b == 3 {
                    assert_eq!(
                        g[mu][a][b], 0.0,
                        "{metric:?} at ({x}, {y}, {z}): Γ^{mu}_{a}{b}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_table_does_not_depend_on_the_observer() {
    let s = off_axis_lit_floor(24, 8);
    let mut other = s.clone();
    other.observer.event = Event::new(1234.5, -0.3, 0.7, 0.2);
    other.observer.velocity = LocalVelocity::new(0.4, [0.0, 1.0, 0.0]).expect("a velocity");
    let (a, b) = (KernelInput::new(&s), KernelInput::new(&other));
    assert_ne!(a.uniforms, b.uniforms);
    assert_eq!(a.table, b.table);
}

/// `scene` with every time (the observer's, the falling balls' starts) later by `dt`.
fn later(mut scene: scene::Scene, dt: f64) -> scene::Scene {
    scene.observer.event.t += dt;
    for o in &mut scene.objects {
        if let Motion::Geodesic { start, .. } = &mut o.motion {
            start.t += dt;
        }
    }
    scene
}

#[test]
fn balls_at_rest_and_in_free_fall_late_in_time_agree_with_the_cpu() {
    // An off-axis moving observer 2 a after a falling ball's start, with a ball at rest, a lit
    // floor and a light; Minkowski space's ball at rest and fast ball. 10⁵ is far beyond f32's
    // digits: a start time the kernel took whole, not relative to the observer's, would move
    // the falling ball.
    for s in [off_axis_lit_floor(60, 20), scene(MINKOWSKI_TWO_BALLS)] {
        let late = later(s, 1e5);
        let a = agreement(&late, KERNEL);
        a.assert_holds();
        assert!(a.seen > 50, "{a:?}");
    }
}

#[test]
fn the_observer_uniforms_are_spacetimes_static_frame_and_isometry() {
    // The host makes them (the kernel reads them, columns e0..e3 of a GLSL mat4, and the
    // isometry's disc point, z₀ and rotation): an off-axis observer in Gödel's universe, one
    // in Minkowski space. The off-axis scenes above and in the agreement suite trace with them.
    for s in [off_axis_lit_floor(24, 8), scene(MINKOWSKI_TWO_BALLS)] {
        let e = s.observer.event;
        let u = KernelInput::new(&s).uniforms.observer;
        let at = Event::new(0.0, e.x, e.y, e.z);
        let frame = s.metric.static_frame(at);
        for (a, leg) in frame.e.iter().enumerate() {
            let column: Vec<f32> = leg.to_array().iter().map(|&c| c as f32).collect();
            assert_eq!(
                u.obs_static[4 * a..4 * a + 4],
                column[..],
                "{}: e{a}",
                s.name
            );
        }
        match s.metric.godel_a() {
            Some(a) => {
                assert!(e.x.hypot(e.y) > 0.1, "an off-axis observer");
                let to = Isometry::to_origin(a, e);
                let want = [to.w0.re, to.w0.im, to.z0, to.rotation].map(|c| c as f32);
                assert_eq!(u.obs_to, want, "{}", s.name);
                // It sends the observer's event (time relative: 0) to the origin.
                let o = Isometry::to_origin(a, at).apply(at);
                assert!(o.to_array().iter().all(|c| c.abs() < 1e-12), "{o:?}");
            }
            None => {
                let identity: Vec<f32> = (0..16).map(|i| f32::from(i % 5 == 0)).collect();
                assert_eq!(u.obs_static[..], identity[..], "{}", s.name);
                assert_eq!(u.obs_to, [0.0; 4], "{}", s.name);
            }
        }
    }
}
