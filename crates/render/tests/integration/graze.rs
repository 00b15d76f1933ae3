//! A shallow graze of a ball in free fall: the exact and the numeric tracer find the same
//! hit. At 2200×250 the reference scene has rays that dip ~0.004 (2 % of the radius) into
//! the falling ball in their second loop, for a λ-stretch of ~0.07. The exact tracer's long
//! closed-form segments once carried a stale proper-time seed from one probe to the next:
//! the match from that seed called the points inside "far", and its estimate (positive)
//! hid the graze, so the exact ray went on to a later image of the ball or escaped.

use crate::common::{self, tracer};

/// The built-in reference scene at 2200×250, one ray per pixel, traced by `method`.
fn reference(method: &str) -> scene::Scene {
    common::reference_scene(method, 2200, 250)
}

/// Pixels where the rays graze the ball (found by comparing the two tracers' full renders):
/// the numeric tracer hits it near λ = 7.42; so must the exact one, with the same record to
/// f32 rounding.
#[test]
fn exact_and_numeric_tracers_agree_on_a_shallow_graze() {
    let (numeric, exact) = (reference("numeric"), reference("exact"));
    let (tn, te) = (tracer(&numeric), tracer(&exact));
    let (mut sn, mut se) = (tn.scratch(), te.scratch());
    for (col, row) in [(875, 120), (879, 118), (877, 130)] {
        let n = numeric
            .observer
            .pixel_direction(&numeric.camera, col, row)
            .unwrap();
        let rn = tn.trace(n, &mut sn).record;
        let re = te.trace(n, &mut se).record;
        assert!(
            rn.is_hit() && (rn.lambda - 7.42).abs() < 0.02,
            "({col}, {row}) numeric: {rn:?}"
        );
        assert_eq!(re.object, rn.object, "({col}, {row}) exact: {re:?}");
        for (e, n) in [
            (re.lambda, rn.lambda),
            (re.t_emit, rn.t_emit),
            (re.u, rn.u),
            (re.v, rn.v),
        ] {
            assert!(
                (e - n).abs() < 1e-5,
                "({col}, {row}): exact {re:?}, numeric {rn:?}"
            );
        }
    }
}
