#!/usr/bin/env bash
# The GPU kernel on a real GPU (docs/physics.md, "The GPU kernel"): the agreement suite (the
# kernel against the CPU exact tracer, issue 22's tolerances), the injected driver faults, the
# runtime check, `godel render --gpu` of the reference scene at 1920×1080 and the kernel bench,
# all against whatever EGL driver the machine has (NVIDIA's on a lent GPU machine).
#
# Two steps, because the GPU machine has no network and no Rust toolchain:
#
#   bash scripts/gpu-device-check.sh build   # here: builds the binaries, stages them (and the
#                                            # EGL loader's Debian packages) in target/device-check
#   bash scripts/gpu-device-check.sh run     # there, in a copy of this repository with
#                                            # target/device-check carried along: runs them,
#                                            # the log in $OUT/gpu-device-check.log (or stdout)
#
# With the device tool: run(command="bash scripts/gpu-device-check.sh run",
# carry=["target/device-check"], timeout_s=540). Every step is bounded by `timeout` and no
# test starts after DEADLINE (340 s), so the whole ends within 8 minutes; the summary at the
# end (ok/FAILED/not started per step, with seconds) and the renders' and the bench's rays/s
# in the log are the figures for BENCHMARKS.md ("GPU kernel").
set -uo pipefail
cd "$(dirname "$0")/.."
stage=target/device-check
# The gpu crate's test binary, and its modules that need a GPU; the others (kernel_rules,
# glslang, softpipe, table) check Mesa, glslang or text.
tests=(integration)
modules='agreement|faults|check|probes|rounds'
# The tests run there, most telling first: NVIDIA's driver took 16-60 s to compile each
# kernel variant (BENCHMARKS.md, "On an NVIDIA H200"), and each scene and each mutation is a
# variant, so the whole suite may not fit; the mutation tests (`*_is_caught`) check the
# suite's power, not the driver, and come last. Each test is its own step, none started
# after DEADLINE seconds.
ordered=(
    "integration check::a_correct_trace_passes_and_a_wrong_one_is_refused"
    "integration probes::elementary_functions_match_std"
    "integration probes::closed_forms_match_spacetime_closed_form"
    "integration probes::isometries_match_spacetime_isometry"
    "integration probes::shadow_rays_match_spacetime_connect"
    "integration rounds::records_do_not_depend_on_tiles_or_budgets"
    "integration rounds::bisections_resumed_at_their_checkpoints_give_the_same_records"
    "integration rounds::lit_floors_are_out_of_work_on_the_gpu_no_more_often_than_on_the_cpu"
    "integration agreement::the_lit_examples_agree"
    "integration agreement::the_falling_ball_of_the_reference_scene_agrees"
    "integration agreement::an_off_axis_observer_moving_at_nine_tenths_of_c_agrees"
    "integration agreement::the_floor_grid_with_its_light_agrees"
    "integration agreement::twenty_eight_images_of_a_falling_ball_agree"
    "integration agreement::universes_with_a_half_and_a_two_agree"
    "integration agreement::an_observer_inside_spheres_sees_their_inner_surfaces_alike"
    "integration agreement::a_fisheye_dome_agrees_also_outside_its_circle"
    "integration agreement::minkowski_rays_are_straight_on_both"
    "integration agreement::the_static_examples_agree"
    "integration faults::a_driver_that_loses_the_probe_stores_is_caught"
    "integration faults::a_nan_blind_finiteness_test_changes_no_record"
    "integration faults::a_probe_answering_nan_is_caught_and_its_samples_marked_failed"
    "integration check::two_percent_and_at_least_two_disagreements_are_allowed"
    "integration check::samples_the_gpu_left_out_of_work_are_disagreements"
    "integration probes::the_metric_and_its_inverse_match_spacetime_godel"
    "integration probes::the_metric_and_its_inverse_match_spacetime_minkowski"
    "integration probes::christoffel_and_normal_displacement_match_spacetime"
    "integration probes::static_and_boosted_frames_match_spacetime_frame_godel"
    "integration probes::static_and_boosted_frames_match_spacetime_frame_minkowski"
    "integration probes::camera_directions_match_scene_camera"
    "integration probes::transport_matches_spacetime_transport"
    "integration probes::rejections_are_safe_and_match_render_reject"
    "integration probes::texture_coordinates_match_render_target"
    "integration agreement::a_kernel_without_loop_copies_is_caught"
    "integration agreement::a_kernel_without_occlusion_is_caught"
    "integration agreement::a_kernel_whose_falling_balls_stand_still_is_caught"
    "integration agreement::a_kernel_without_the_observers_boost_is_caught"
    "integration agreement::a_kernel_without_the_observers_isometry_is_caught"
    "integration agreement::a_kernel_without_the_polarization_transport_is_caught"
)
DEADLINE=${DEADLINE:-340}

build() {
    set -e
    rm -rf "$stage"
    mkdir -p "$stage/bin" "$stage/gl"
    cargo build --quiet -p godel --bin godel
    # The test and bench executables, as cargo names them (a hash in the file name); the bench
    # in the test profile (optimized, Cargo.toml): the GPU's time is the driver's anyway.
    local json
    json=$(cargo test -p gpu --tests --benches --no-run --message-format=json)
    for name in "${tests[@]}" kernel; do
        local exe
        exe=$(printf '%s\n' "$json" | python3 -c '
import json, sys
name = sys.argv[1]
for line in sys.stdin:
    try:
        m = json.loads(line)
    except ValueError:
        continue
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["name"] == name:
        print(m["executable"])
' "$name" | tail -n 1)
        [ -n "$exe" ] || { echo "no executable for $name" >&2; exit 1; }
        cp "$exe" "$stage/bin/$name"
    done
    cp target/debug/godel "$stage/bin/godel"
    strip "$stage"/bin/*
    # The binaries find the scenes by the path this repository had when they were built.
    pwd > "$stage/ROOT"
    # EGL through glvnd, which dispatches to the vendor's driver (NVIDIA's brings only the
    # vendor library): Debian's loader packages, unpacked there.
    (cd "$stage/gl" && apt-get download -qq libegl1 libglvnd0 libgles2 libopengl0 >/dev/null)
    tar -C "$stage" -cJf "$stage.tar.xz" bin gl ROOT
    rm -rf "$stage/bin" "$stage/gl"
    mv "$stage.tar.xz" "$stage/bundle.tar.xz"
    du -sh "$stage"
    echo "carry $stage (under 64 MiB with the working tree), then: bash $0 run"
}

# One step: its name, a limit in seconds, the command; prints ok/FAILED and the seconds.
results=()
step() {
    local name=$1 limit=$2
    shift 2
    echo "=== $name"
    local start end rc
    start=$(date +%s.%N)
    timeout "$limit" "$@"
    rc=$?
    end=$(date +%s.%N)
    local took
    took=$(python3 -c "print(f'{$end - $start:.1f}')")
    local verdict=ok
    [ "$rc" -eq 0 ] || verdict="FAILED (exit $rc)"
    results+=("$name: $verdict in $took s")
    echo "=== $name: $verdict in $took s"
}

run() {
    SECONDS=0
    [ -f "$stage/bundle.tar.xz" ] || { echo "no $stage/bundle.tar.xz: run 'bash $0 build' here first and carry $stage" >&2; exit 2; }
    local work
    work=$(mktemp -d)
    tar -C "$work" -xJf "$stage/bundle.tar.xz"
    # The repository's path at build time, pointing here (the binaries read scenes there).
    local root
    root=$(cat "$work/ROOT")
    if [ "$root" != "$PWD" ] && [ ! -e "$root" ]; then
        mkdir -p "$(dirname "$root")" && ln -s "$PWD" "$root"
    fi
    # The EGL loader where the machine has none (unpacked over /, as the device notes say).
    if ! ldconfig -p | grep -q 'libEGL.so.1 '; then
        for f in "$work"/gl/*.deb; do dpkg -x "$f" /; done
        ldconfig
    fi
    local vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
    [ -f "$vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
    command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version --format=csv
    local bin=$work/bin
    local out
    out=$(mktemp -d)
    # The reference scene at 1920×1080, one ray a pixel: three runs (the first compiles).
    for i in 1 2 3; do
        step "render --gpu reference 1920x1080 run $i" 120 \
            "$bin/godel" render scenes/reference.toml --gpu --width 1920 --height 1080 \
            --samples 1 -q -o "$out"
    done
    step "bench kernel" 150 "$bin/kernel" --bench --warm-up-time 1 --measurement-time 3
    for entry in "${ordered[@]}"; do
        if [ "$SECONDS" -gt "$DEADLINE" ]; then
            results+=("test $entry: not started (past ${DEADLINE} s)")
            continue
        fi
        read -r t name <<<"$entry"
        step "test $t $name" 120 "$bin/$t" --exact "$name" --nocapture
    done
    # Every test of the suite is listed above (a new one must be added there).
    for t in "${tests[@]}"; do
        local listed
        listed=$("$bin/$t" --list 2>/dev/null | sed -n 's/: test$//p' | grep -E "^($modules)::")
        for name in $listed; do
            printf '%s\n' "${ordered[@]}" | grep -qx "$t $name" \
                || results+=("test $t $name: not in the script's list")
        done
    done
    echo "=== summary"
    printf '%s\n' "${results[@]}"
    rm -rf "$work" "$out"
}

case "${1:-}" in
    build) build ;;
    run)
        if [ -n "${OUT:-}" ]; then
            run 2>&1 | tee "$OUT/gpu-device-check.log"
        else
            run
        fi
        ;;
    *) echo "usage: bash $0 build|run" >&2; exit 2 ;;
esac
