#!/bin/sh
# Builds sgapi with clang under AddressSanitizer and UndefinedBehaviorSanitizer and runs the ctest
# suite in that build. Every sanitizer report aborts its test, so any report fails the run.
#
#   tools/sanitize.sh BUILD_DIR [JOBS]
set -eu
build=${1:?usage: tools/sanitize.sh BUILD_DIR [JOBS]}
jobs=${2:-2}
src=$(cd "$(dirname "$0")/.." && pwd)

san="-fsanitize=address,undefined"
# UBSan's pointer-overflow check is left out: it instruments every address computation of the
# SIMD bodies, and took half of this build's time (428 s of compiling against 209 s without, on
# two cores); an access out of bounds is AddressSanitizer's to catch.
nocheck="-fno-sanitize=pointer-overflow"
# sgapi-ref is left out: it runs Mesa's lavapipe, which is not instrumented and reports its own
# leaks; the image checks against the committed golden/ renders still run.
# -O1 with line tables, not -O0 with full debug information: at -O0 every inlined SIMD body stays
# unoptimised in each variant, and each test binary came to 300 MB (9 GB for the folder); -O1 is
# ASan's own advice, keeps file and line in every report, and the folder takes 0.8 GB.
# -Wno-pass-failed: the example shaders' "omp simd" loops are not vectorised at -O1.
# The SIMD variants keep ASan and UBSan's arithmetic checks but not UBSan's pointer checks
# (alignment, null, object-size, bounds) nor ASan's use-after-scope: ASan sees their memory
# accesses already, their locals live for the whole function, and on their large inlined functions
# those checks cost clang more than twice the compile time of the rest of the build. Their
# address checks are calls into ASan's runtime, not inlined code: the same checks, in a third of
# the compile time (blend_avx2.c: 49 s against 140 s), their tests a little slower.
simd="-fno-sanitize=alignment,null,object-size,bounds;-fno-sanitize-address-use-after-scope;-fsanitize-address-outline-instrumentation"
CC=clang cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Debug -DSGAPI_SIMD_FLAGS="$simd" \
    -DCMAKE_C_FLAGS_DEBUG="-O1 -gline-tables-only" \
    -DCMAKE_C_FLAGS="$san $nocheck -fno-sanitize-recover=all -fno-omit-frame-pointer -Wno-pass-failed" \
    -DCMAKE_EXE_LINKER_FLAGS="$san" -DCMAKE_SHARED_LINKER_FLAGS="$san" \
    -DSGAPI_BUILD_REFERENCE=OFF -DSGAPI_SHADE_SIMD_CASES=17500
cmake --build "$build" -j "$jobs"

# Skipped: install_consumer, which checks packaging, not code: its consumer is compiled by the
# system cc, which cannot link objects built against clang's sanitizer runtime; the browser
# checks of the regression report and the CI examples, which run Chromium and Python, not sgapi;
# regression_report, which renders again scenes the golden_* checks render (its code runs in
# regression_workflow); and slurm_batch, which checks the job scripts and the cluster's start and
# stop, rendering scenes the golden_* checks render (a minute under the sanitizers); and
# threads_identical, whose renders of every scene at 2, 3 and 5 threads the ThreadSanitizer stage
# makes again (tools/tsan.sh); and bin_memory_identical, every scene five times at two bin memory
# limits, whose flushes alloc_fail makes under the sanitizers with a smaller limit.
# test_shade_simd takes a quarter of its random cases (SGAPI_SHADE_SIMD_CASES): each one reads
# its textures as the rest do, and the plain suite runs them all. test_line likewise a quarter of
# its random segments (SG_LINE_SEGMENTS): each walks the same code, against an exact reference
# that takes most of the test's 30 s here.
cd "$build"
SG_LINE_SEGMENTS=25000 \
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --output-on-failure --no-tests=error -j "$jobs" -E '^(install_consumer|report_browser|ci_examples|regression_report|slurm_batch|threads_identical|bin_memory_identical)$'
