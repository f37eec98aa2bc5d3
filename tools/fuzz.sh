#!/bin/sh
# Builds the libFuzzer targets of the file loaders with clang and runs each for FUZZ_SECONDS
# seconds (default 60); fails when any target finds a crash, a hang or a sanitizer report.
#
# Corpora grow in $FUZZ_BUILD/corpus/<target>/ (seeded from scenes/ on every run), crash inputs
# land in $FUZZ_BUILD/crashes/<target>/, libFuzzer's output in $FUZZ_BUILD/logs/<target>.log.
# FUZZ_BUILD defaults to build-fuzz. See docs/fuzzing.md.
set -eu

cd "$(dirname "$0")/.."
BUILD=${FUZZ_BUILD:-build-fuzz}
SECONDS_EACH=${FUZZ_SECONDS:-60}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
TARGETS="obj scene image off mtl api"

CC=clang cmake -S . -B "$BUILD" -DSGAPI_BUILD_FUZZERS=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build "$BUILD" -j "$JOBS" --target fuzz_obj fuzz_scene fuzz_image fuzz_off fuzz_mtl \
    fuzz_api

BUILD=$(cd "$BUILD" && pwd)
# The scene target's scratch folders go here rather than to the system's temporary folder.
mkdir -p "$BUILD/tmp"
TMPDIR="$BUILD/tmp"
export TMPDIR

# Seeds: the project's own files, copied in afresh so they track scenes/.
seed() { # target, files...
    dir="$BUILD/corpus/$1"
    shift
    mkdir -p "$dir"
    for f in "$@"; do
        [ -f "$f" ] && cp "$f" "$dir/seed-$(basename "$f")"
    done
    return 0
}
# The committed, minimised corpora (tests/fuzz/corpus/, replayed by make test) seed them too.
seed obj scenes/assets/*.obj tests/fuzz/corpus/obj/*
seed scene scenes/default.json scenes/hard/*.json tests/fuzz/corpus/scene/*
seed image scenes/assets/*.png
# OFF and MTL: the project's OFF file and the small seeds of tests/fuzz/seeds/ (every header
# variant, face colours as integers and floats; every MTL statement read, texture options).
seed off scenes/assets/*.off tests/fuzz/seeds/off/*
seed mtl tests/fuzz/seeds/mtl/*
# The API sequences: the committed corpus (replayed by make test) is the seed.
seed api tests/fuzz/corpus/api/*
# The scene seeds once more with their mesh and texture paths pointed at the files of the target's
# scratch folder, so mutations start from drawable scenes rather than from missing files.
for f in scenes/default.json scenes/hard/*.json; do
    [ -f "$f" ] || continue
    sed -e 's#"[^"]*\.obj"#"tri.obj"#g' -e 's#"[^"]*\.png"#"tex.png"#g' \
        -e 's#"[^"]*\.bmp"#"tex.png"#g' "$f" \
        >"$BUILD/corpus/scene/seed-scratch-$(basename "$f")"
done

failed=""
mkdir -p "$BUILD/logs"
# The committed reproducers first, under the sanitizers and with the image decoder instrumented:
# the plain replay test (ctest fuzz_regressions) cannot see an over-read inside the decoder.
for t in $TARGETS; do
    [ -d tests/fuzz/regressions/"$t" ] || continue
    log="$BUILD/logs/$t-regressions.log"
    if ! "$BUILD/tests/fuzz/fuzz_$t" tests/fuzz/regressions/"$t"/* >"$log" 2>&1; then
        echo "fuzz_$t FAILED on a committed reproducer; the end of $log:"
        tail -n 30 "$log"
        failed="$failed $t"
    fi
done

for t in $TARGETS; do
    mkdir -p "$BUILD/crashes/$t"
    opts=""
    [ -f "tests/fuzz/$t.dict" ] && opts="-dict=tests/fuzz/$t.dict"
    # The image seeds are whole textures of up to some 500 KB; mutating inputs that large decodes
    # tens per second, while 64 KB holds every header and chunk layout.
    [ "$t" = image ] && opts="$opts -max_len=65536"
    # A sequence of up to 192 calls fits in 4 KB.
    [ "$t" = api ] && opts="$opts -max_len=4096"
    log="$BUILD/logs/$t.log"
    echo "fuzz_$t: ${SECONDS_EACH}s, corpus $BUILD/corpus/$t, log $log"
    # -timeout: an input taking longer than this is a hang and a failure, like a crash.
    # shellcheck disable=SC2086
    if "$BUILD/tests/fuzz/fuzz_$t" -max_total_time="$SECONDS_EACH" -timeout=20 \
        -artifact_prefix="$BUILD/crashes/$t/" -print_final_stats=1 $opts \
        "$BUILD/corpus/$t" >"$log" 2>&1; then
        # libFuzzer's last status line: runs, coverage, corpus, exec/s.
        grep -E '^#[0-9]+[[:space:]]+DONE|^Done ' "$log" || true
    else
        echo "fuzz_$t FAILED; the end of its log:"
        tail -n 30 "$log"
        failed="$failed $t"
    fi
done

if [ -n "$failed" ]; then
    echo "fuzzing found problems in:$failed; inputs in $BUILD/crashes/<target>/" >&2
    echo "reproduce: $BUILD/tests/fuzz/fuzz_<target> <input>" >&2
    exit 1
fi
echo "fuzzing found nothing in $SECONDS_EACH s per target"
