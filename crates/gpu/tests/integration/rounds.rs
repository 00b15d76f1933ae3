//! The kernel's rounds (docs/physics.md, "The GPU kernel", "Bounds of a GPU" and "Rounds"): a
//! sample is traced in rounds, each taking it on from its last checkpoint, so its record does
//! not depend on how its work is cut (tile sizes, budgets of passes, llvmpipe's loop limit,
//! timing), and the GPU has no bound the CPU exact tracer has not: on lit floors seen by a
//! moving off-axis observer, with a ball falling at 0.8 c, for a from 0.5 to 2 and max_past up
//! to 30, it marks `work limit` no more often than the CPU (before the rounds, such a scene at
//! 360×70 had hundreds of GPU samples out of work, the CPU none, and two runs differed).

use crate::common::{self, agreement, bits, lit_floor};
use gpu::{GpuTracer, KernelInput, Tiling, Traced, KERNEL};
use render::driver::NoProgress;

fn same_bytes(a: &Traced, b: &Traced) -> bool {
    let records = |t: &Traced| t.records.iter().map(bits).collect::<Vec<_>>();
    let lights = |t: &Traced| {
        (t.lights.iter())
            .map(|l| l.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    };
    records(a) == records(b) && lights(a) == lights(b)
}

#[test]
fn records_do_not_depend_on_tiles_or_budgets() {
    // A lit floor, a ball falling at 0.8 c, an off-axis observer at 0.6 c, a = 0.5 and
    // max_past 30 (twenty and more windings): before the rounds, 160 of its 400 samples at
    // 40×10 were out of work on the GPU, none on the CPU, and which ones depended on the tiles.
    let scene = lit_floor(0.5, 30.0, 16, 4);
    let tracer = GpuTracer::new(KernelInput::new(&scene)).expect("a GPU context");
    let cuts = [
        // Many small tiles and rounds of 8 passes: a sample crosses many rounds, and
        // llvmpipe groups it with other neighbours.
        Tiling {
            side: Some(5),
            first_budget: 8,
        },
        // One tile of the whole grid, long rounds: llvmpipe's loop limit cuts them.
        Tiling {
            side: Some(64),
            first_budget: 1 << 16,
        },
        Tiling::default(),
    ];
    let traced: Vec<Traced> = (cuts.iter())
        .map(|&t| tracer.trace_with(&NoProgress, t).expect("trace"))
        .collect();
    let rounds: Vec<u64> = traced.iter().map(|t| t.rounds).collect();
    eprintln!("rounds: {rounds:?}");
    // The work was cut differently: many more rounds with small budgets and tiles.
    assert!(rounds[0] > 4 * rounds[1], "rounds {rounds:?}");
    let hits = (traced[0].records.iter())
        .filter(|r| r.status == datafile::RayStatus::Hit)
        .count();
    assert!(hits > 10, "the scene shows its objects: {hits} hits");
    for (t, cut) in traced[1..].iter().zip(&cuts[1..]) {
        assert!(
            same_bytes(&traced[0], t),
            "the records of {cut:?} differ from those of {:?}",
            cuts[0]
        );
    }
}

#[test]
fn bisections_resumed_at_their_checkpoints_give_the_same_records() {
    // A bisection is a checkpoint every SPAN_CHECK probes; a round resumes it by going through
    // its loop again without bisecting. With a checkpoint every 2 probes and rounds of 8 passes
    // in small tiles, nearly every bisection of the reference scene (balls at rest and in free
    // fall, whose probes take τ seeds) is cut and resumed many times; its records must be the
    // bits of the kernel as it is, traced in long rounds (before these checkpoints, such a
    // bisection of tens of thousands of probes could not fit a round on llvmpipe: 4 samples of
    // the reference scene at 550×63×4 were out of work, none on the CPU).
    // Two overlapping balls at rest, the nearer listed first: a ray that meets the first
    // searches the second in the same segment only up to the first's crossing, which the
    // resumed bisection must know.
    let overlapping = common::scene(
        "name = \"overlapping\"\n\
         [spacetime]\nmetric = \"godel\"\na = 1.0\n\
         [observer]\ntime = 0.0\nposition = { x = 0.0, y = 0.0, z = 0.0 }\nforward = [1, 1.5, 0]\nup = [0, 0, 1]\n\
         [camera]\nkind = \"pinhole\"\nfov_deg = 100.0\nwidth = 24\nheight = 12\n\
         [trace]\nmax_past = 10.0\n\
         [[object]]\nname = \"front\"\nradius = 0.3\nmotion = { kind = \"rest\", position = { x = 1.0, y = 0.0, z = 0.0 } }\n\
         [[object]]\nname = \"behind\"\nradius = 0.3\nmotion = { kind = \"rest\", position = { x = 1.1, y = 0.25, z = 0.0 } }\n",
    );
    let every = "const int SPAN_CHECK = 256;";
    assert!(KERNEL.contains(every), "the kernel's checkpoint spacing");
    let often = KERNEL.replace(every, "const int SPAN_CHECK = 2;");
    // Each scene with the objects it shows.
    let scenes = [
        (common::sized(common::example("reference"), 48, 12), vec![0]),
        (overlapping, vec![0, 1]),
        // Minkowski's straight rays: searched stretch by stretch, not loop by loop.
        (
            common::sized(common::scene(common::MINKOWSKI_TWO_BALLS), 32, 24),
            vec![0],
        ),
    ];
    for (scene, seen) in scenes {
        let cut = GpuTracer::with_kernel(KernelInput::new(&scene), &often)
            .expect("a GPU context")
            .trace_with(
                &NoProgress,
                Tiling {
                    side: Some(6),
                    first_budget: 8,
                },
            )
            .expect("trace");
        let whole = GpuTracer::new(KernelInput::new(&scene))
            .expect("a GPU context")
            .trace_with(&NoProgress, Tiling::default())
            .expect("trace");
        eprintln!(
            "{}: rounds: cut {}, whole {}",
            scene.name, cut.rounds, whole.rounds
        );
        assert!(
            cut.rounds > 20 * whole.rounds,
            "rounds {} and {}",
            cut.rounds,
            whole.rounds
        );
        let hits = |object: i32| {
            (whole.records.iter())
                .filter(|r| r.status == datafile::RayStatus::Hit && r.object == object)
                .count()
        };
        for object in seen {
            assert!(
                hits(object) > 5,
                "{}: {} hits of object {object}",
                scene.name,
                hits(object)
            );
        }
        assert!(
            same_bytes(&cut, &whole),
            "{}: resumed bisections changed records",
            scene.name
        );
    }
}

#[test]
fn lit_floors_are_out_of_work_on_the_gpu_no_more_often_than_on_the_cpu() {
    for (a, max_past) in [(0.5, 30.0), (1.0, 10.0), (1.5, 25.0), (2.0, 30.0)] {
        let scene = lit_floor(a, max_past, 40, 10);
        let m = agreement(&scene, KERNEL);
        eprintln!("a = {a}, max_past = {max_past}: {m:?}");
        let [gpu, cpu] = m.work_limit;
        assert!(gpu <= cpu, "work limit: GPU {gpu}, CPU {cpu}");
        if a >= 1.0 {
            m.assert_holds();
            continue;
        }
        // a = 0.5, max_past 30: twenty and more windings. The same objects, shifts and times
        // as everywhere, but 4 of 68 lit samples differ in light by 0.4 to 9 %: two where a
        // shadow ray grazes a ball (without the balls they agree), two where two roots meet
        // near a caustic (area distance 0.085), which f32 and f64 resolve apart
        // (docs/physics.md, "The GPU kernel"); the polarization's 99.9th percentile is 1.1e-4.
        assert!(m.same >= common::SAME || m.differ <= 1, "{m:?}");
        let g = m.g_median <= common::G_MEDIAN && m.g_p999 <= common::G_P999;
        assert!(g && m.t_p999 <= common::T_P999, "{m:?}");
        let pol = m.pol_p999 <= 2.0 * common::POL_P999;
        assert!(m.light_within >= 0.9 && pol, "{m:?}");
    }
}
