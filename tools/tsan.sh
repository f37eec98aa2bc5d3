#!/bin/sh
# Builds sgapi-render and the threaded tests with clang under ThreadSanitizer in BUILD_DIR, then
# renders the project's scene files at 2, 3 and 5 raster threads (requiring the same images at 3
# and 5 as at 2; ctest's threads_identical holds them to one thread's), a short turntable written by two writer threads, and the threaded tests (the allocation
# failure script, API sequences, the animation example). Any data race or other ThreadSanitizer
# report fails the run (exit 1). The one suppression file, tools/tsan.supp, names Mesa's
# lavapipe alone (the reference renderer, not built here).
#
#   tools/tsan.sh BUILD_DIR [JOBS]
set -eu
build=${1:?usage: tools/tsan.sh BUILD_DIR [JOBS]}
jobs=${2:-2}
src=$(cd "$(dirname "$0")/.." && pwd)

san="-fsanitize=thread"
# The built-in shaders in their baseline compilation alone: a stage runs within one thread, and the
# plain build holds its other compilations to the baseline's bits (test_shader_copies).
# Line tables, not full debug information: a report names file and line all the same, and the
# SIMD variants' large inlined functions compile in two thirds of the time.
CC=clang cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DCMAKE_C_FLAGS="$san -fno-omit-frame-pointer" \
    -DCMAKE_EXE_LINKER_FLAGS="$san" -DCMAKE_SHARED_LINKER_FLAGS="$san" \
    -DSGAPI_BUILD_REFERENCE=OFF -DSGAPI_SHADER_COPIES=OFF >/dev/null
# Only what runs below, to keep the stage short.
cmake --build "$build" -j "$jobs" --target sgapi-render test_alloc_fail test_api_seq \
    animate_objects

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# halt_on_error: the first report ends the program with exitcode, which fails this script.
# The suppression file's path quoted: the checkout's may hold blanks.
TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1 suppressions='$src/tools/tsan.supp'"
export TSAN_OPTIONS

# Every scene file but scale.json (millions of triangles a scene: for sgapi-bench).
set --
for f in "$src"/scenes/*.json; do [ "${f##*/}" = scale.json ] || set -- "$@" "$f"; done
for t in 2 3 5; do
    echo "tsan: sgapi-render, every scene file, $t threads"
    "$build/apps/sgapi-render" "$@" -o "$out/$t" --threads "$t" --quiet \
        --png-level 0 >/dev/null
done
for t in 3 5; do
    for png in "$out/2"/*.png; do
        cmp -s "$png" "$out/$t/$(basename "$png")" ||
            { echo "tsan: $(basename "$png") differs at $t threads" >&2; exit 1; }
    done
done
echo "tsan: a turntable of 4 frames, 3 threads, 2 writers"
"$build/apps/sgapi-render" "$src/scenes/shadows.json" --scene shadow_teapots -o "$out/turn" \
    --turntable 4 --threads 3 --writers 2 --quiet >/dev/null
# Side by side: none of the three keeps two cores busy throughout, so together they end sooner.
echo "tsan: allocation failures at 3 and 5 threads, the committed API sequences at 1 and 3 threads"
mkdir "$out/log"
"$build/tests/test_alloc_fail" 3 >"$out/log/alloc_fail_3" 2>&1 &
alloc3=$!
"$build/tests/test_alloc_fail" 5 >"$out/log/alloc_fail_5" 2>&1 &
alloc5=$!
"$build/tests/test_api_seq" "$src/tests/fuzz/corpus" >"$out/log/api_seq" 2>&1 &
seq=$!
failed=
wait "$alloc3" || failed="$failed alloc_fail_3"
wait "$alloc5" || failed="$failed alloc_fail_5"
wait "$seq" || failed="$failed api_seq"
cat "$out/log/alloc_fail_3" "$out/log/alloc_fail_5"
case $failed in *api_seq*) cat "$out/log/api_seq" >&2 ;; esac
[ -z "$failed" ] || { echo "tsan: failed:$failed" >&2; exit 1; }
echo "tsan: the animation example, 3 threads"
"$build/apps/examples/animate_objects" 40 32 >/dev/null
echo "tsan: no report"
