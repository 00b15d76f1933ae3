#!/usr/bin/env bash
# Checks that two builds of godel write byte-identical files for every example scene:
#   scripts/same-outputs.sh OLD_GODEL NEW_GODEL [--scale K] [--mpi NEW_MPI_GODEL] [--records TOOL]
# Each scene in scenes/*.toml is rendered with both methods (numeric and exact) by both
# binaries, and the EXR and PNG compared with cmp; the new binary's parts 1/3..3/3, merged,
# must equal the old single run too (and, with --mpi, `mpirun -n 2` of the MPI build);
# a stereo scene, which cannot be split, is compared file by file (both eyes, the picture).
# --scale K divides every image's width and height by K (a quicker check). --records TOOL
# (the `same_records` example of the datafile crate) accepts data files whose bytes differ
# when their records, lights and header are the same bit for bit (a change of EXR
# compression). Exit 1 on any difference. Used for refactors that promise "no behaviour
# change".
set -euo pipefail
old=$1 new=$2
shift 2
scale=1 mpi="" records=""
while [ $# -gt 0 ]; do
    case $1 in
        --scale) scale=$2; shift 2 ;;
        --mpi) mpi=$2; shift 2 ;;
        --records) records=$2; shift 2 ;;
        *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
for scene in scenes/*.toml; do
    base=$(basename "$scene" .toml)
    for method in numeric exact; do
        s="$work/$base-$method.toml"
        # The same scene (every example sets `method`) with this method, its own name and,
        # with --scale, a smaller image.
        sed -e "s/^method *=.*/method = \"$method\"/" -e "0,/^name *=.*/s//name = \"$base-$method\"/" \
            -e "s/^\(width\|height\) *= *\([0-9][0-9]*\) *$/echo \"\1 = \$(( \2 \/ $scale > 4 ? \2 \/ $scale : 4 ))\"/e" \
            "$scene" > "$s"
        "$old" render "$s" -o "$work/old" -q 2>/dev/null
        "$new" render "$s" -o "$work/new" -q 2>/dev/null
        if grep -q '^ *stereo *=' "$s"; then
            # Both eyes in one process (no --part, no MPI ranks): every file the old build
            # wrote (the eyes' data files and the picture) compared with the new one's.
            compared=0
            for f in $(cd "$work/old" && ls "$base-$method".* 2>/dev/null); do
                compared=$((compared + 1))
                if cmp -s "$work/old/$f" "$work/new/$f"; then
                    echo "same   $f"
                else
                    echo "DIFFER $f"; fail=1
                fi
            done
            # No file from the old build (it refused the scene) proves nothing.
            if [ "$compared" -eq 0 ]; then
                echo "NONE   $base-$method (the old build wrote nothing)"; fail=1
            fi
            continue
        fi
        for p in 1 2 3; do "$new" render "$s" --part "$p/3" -o "$work/parts" -q 2>/dev/null; done
        "$new" merge "$work"/parts/"$base-$method".part-*-of-3.exr -o "$work/merged" 2>/dev/null
        for ext in exr png; do
            f="$base-$method.$ext"
            if cmp -s "$work/old/$f" "$work/new/$f" && cmp -s "$work/old/$f" "$work/merged/$f"; then
                echo "same   $f"
            elif [ "$ext" = exr ] && [ -n "$records" ] &&
                "$records" "$work/old/$f" "$work/new/$f" "$work/merged/$f"; then
                echo "same   $f (records; bytes differ)"
            else
                echo "DIFFER $f"; fail=1
            fi
        done
        if [ -n "$mpi" ]; then
            mpirun --allow-run-as-root --oversubscribe -n 2 "$mpi" render "$s" -o "$work/mpi" -q 2>/dev/null
            for ext in exr png; do
                f="$base-$method.$ext"
                if cmp -s "$work/old/$f" "$work/mpi/$f"; then echo "same   $f (mpirun -n 2)"; else echo "DIFFER $f (mpirun -n 2)"; fail=1; fi
            done
        fi
    done
done
exit $fail
