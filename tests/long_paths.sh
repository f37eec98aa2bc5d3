#!/bin/sh
# Every app with paths as a user's may be: a folder over 200 characters deep, a folder name with a
# blank and one with a non-ASCII letter (inside WORK_DIR, made here). The project's scene files
# and their assets are copied there and the apps are run with scene files, models, outputs,
# golden, report and JUnit paths all in it: what they write is where it should be, and a message
# that names such a path names it whole, up to its last words.
#   long_paths.sh RENDER REF BENCH DIFF VIEW SOURCE_DIR WORK_DIR
# REF, BENCH and VIEW are '-' when not built (no Vulkan loader or glslang; no SDL2): then their
# checks are skipped, and said to be.
set -eu
if [ "${1:-}" = --view ]; then # the viewer's part, under a virtual X server (below)
    shift
    view=$1
    scene=$2
    saves=$3
    "$view" "$scene" --scene 01_colored_triangle --size 160x120 --threads 1 --save-dir "$saves" \
        >"$saves/view.log" 2>&1 &
    pid=$!
    trap 'kill $pid 2>/dev/null || true' EXIT
    wid=$(timeout 30 xdotool search --sync --name '^sgapi-view' | head -n 1)
    [ -n "$wid" ] || { echo "FAIL: no sgapi-view window" && cat "$saves/view.log" && exit 1; }
    # The title names the scene file whole once its first second of frames is counted.
    i=0
    until xdotool getwindowname "$wid" | grep -q -F "sgapi-view - $scene - "; do
        i=$((i + 1))
        [ $i -lt 100 ] || { echo "FAIL: title: $(xdotool getwindowname "$wid")" && exit 1; }
        sleep 0.1
    done
    xdotool windowfocus --sync "$wid"
    xdotool key --clearmodifiers F12
    i=0
    while [ ! -f "$saves/frame-0001.png" ]; do
        i=$((i + 1))
        [ $i -lt 300 ] || { echo "FAIL: F12 did not save into $saves" && exit 1; }
        sleep 0.1
    done
    xdotool key --clearmodifiers Escape
    wait $pid || { echo "FAIL: sgapi-view exited with an error" && exit 1; }
    grep -q -F "saved $saves/frame-0001.png" "$saves/view.log" ||
        { echo "FAIL: the viewer did not name its saved frame whole" && exit 1; }
    exit 0
fi
render=$1
ref=$2
bench=$3
diff=$4
view=$5
src=$6
work=$7
rm -rf "$work"
fail() {
    echo "FAIL: $*"
    exit 1
}
# The deep folder: a blank and a non-ASCII letter, then folders of 40 characters until the whole
# absolute path is over 200 characters (whatever the build folder's depth).
mkdir -p "$work"
deep=$(cd "$work" && pwd)/"long path ü"
while [ "$(printf '%s' "$deep" | wc -m)" -le 200 ]; do
    deep="$deep/folder-of-forty-characters-in-a-deep-tree"
done
mkdir -p "$deep/scenes"
echo "deep folder: $(printf '%s' "$deep" | wc -m) characters"
cp -R "$src/scenes/default.json" "$src/scenes/assets" "$deep/scenes/"
mkdir -p "$deep/golden"
cp "$src/golden/01_colored_triangle.png" "$src/golden/04_textured_cube.png" "$deep/golden/"
scenes="$deep/scenes/default.json"
# Each check's output and messages, for a failure to show.
run() { # NAME COMMAND...: stdout and stderr to $deep/NAME.out and .err; the exit status in rc
    name=$1
    shift
    rc=0
    "$@" >"$deep/$name.out" 2>"$deep/$name.err" || rc=$?
}
has() { # FILE TEXT: the file holds the text
    grep -q -F -- "$2" "$1" || fail "$(basename "$1"): no '$2' in: $(cat "$1")"
}

# ---- sgapi-render: scene files, outputs, golden, report and JUnit in the deep folder ----
run render "$render" "$scenes" --scene 01_colored_triangle --scene 04_textured_cube \
    -o "$deep/out" --compare "$deep/golden" --thresholds "$src/golden/thresholds.csv" \
    --report "$deep/report" --junit "$deep/junit/results.xml"
[ $rc -eq 0 ] || fail "render: exit $rc: $(cat "$deep/render.err")"
for f in out/01_colored_triangle.png out/04_textured_cube.png out/04_textured_cube-heat.png \
    report/index.html report/results.json report/img/04_textured_cube.actual.png \
    junit/results.xml; do
    [ -s "$deep/$f" ] || fail "render: no $deep/$f"
done
has "$deep/render.out" "report: $deep/report/index.html"
has "$deep/junit/results.xml" "$deep/report/img/04_textured_cube.heat.png"
# A golden that is missing: the reason names its whole path.
run missing "$render" "$scenes" --scene 02_tris_and_quads -o "$deep/out" \
    --compare "$deep/golden"
[ $rc -eq 1 ] || fail "a missing golden: exit $rc, not 1"
has "$deep/missing.err" \
    "cannot open '$deep/golden/02_tris_and_quads.png': No such file or directory"

# ---- a model with a missing texture: its warning names three deep paths, whole ----
cat >"$deep/no_tex.mtl" <<'MTL'
newmtl a
Kd 1 0.5 0.25
map_Kd missing.png
MTL
cat >"$deep/no_tex.obj" <<'OBJ'
mtllib no_tex.mtl
v 0 0 0
v 1 0 0
v 0 1 0
vt 0 0
vt 1 0
vt 0 1
usemtl a
f 1/1 2/2 3/3
OBJ
run model "$render" "$deep/no_tex.obj" -o "$deep/models" --size 64x48
[ $rc -eq 0 ] || fail "model: exit $rc: $(cat "$deep/model.err")"
[ -s "$deep/models/no_tex.png" ] || fail "model: no $deep/models/no_tex.png"
has "$deep/model.err" "sgapi-render: warning: $deep/no_tex.obj, material 'a' ($deep/no_tex.mtl): \
texture '$deep/missing.png' not found: drawn without it"
# A scene file that is not there: the message names it whole.
run absent "$render" "$deep/scenes/absent.json" -o "$deep/out"
[ $rc -eq 1 ] || fail "a missing scene file: exit $rc, not 1"
has "$deep/absent.err" "cannot open '$deep/scenes/absent.json': No such file or directory"
echo "sgapi-render: scenes, models, outputs, golden, report and JUnit in the deep folder"

# ---- sgapi-diff: two images and a heat map there ----
mkdir -p "$deep/diff"
run diff "$diff" "$deep/out/04_textured_cube.png" "$deep/golden/04_textured_cube.png" \
    --heat "$deep/diff/heat.png"
[ $rc -eq 0 ] || fail "diff: exit $rc: $(cat "$deep/diff.err")"
[ -s "$deep/diff/heat.png" ] || fail "diff: no heat map"
has "$deep/diff.out" "psnr"
echo "sgapi-diff: images and heat map in the deep folder"

# ---- sgapi-ref and sgapi-bench (lavapipe) ----
if [ "$ref" != - ]; then
    run ref "$ref" "$scenes" --scene 01_colored_triangle -o "$deep/ref out"
    [ $rc -eq 0 ] || fail "ref: exit $rc: $(cat "$deep/ref.err")"
    [ -s "$deep/ref out/01_colored_triangle.png" ] || fail "ref: no image in $deep/ref out"
    echo "sgapi-ref: scene file and output in the deep folder"
else
    echo "sgapi-ref not built: skipped"
fi
if [ "$bench" != - ]; then
    # The smallest run: the small scenes of the turntable tests, two frames each.
    mkdir -p "$deep/bench"
    sh "$src/tests/tiny_scenes.sh" "$deep/bench/tiny.json" "$deep"
    run bench "$bench" "$deep/bench/tiny.json" --quick --threads 1 --csv "$deep/bench/times.csv"
    [ $rc -eq 0 ] || fail "bench: exit $rc: $(cat "$deep/bench.err")"
    [ -s "$deep/bench/times.csv" ] || fail "bench: no CSV"
    echo "sgapi-bench: scene file and CSV in the deep folder"
else
    echo "sgapi-bench not built: skipped"
fi

# ---- sgapi-view: the scene file and --save-dir there, under a virtual X server ----
if [ "$view" != - ]; then
    mkdir -p "$deep/saved frames"
    unset SGAPI_VIEW_TEST_INNER
    # Under AddressSanitizer the viewer's leaks go unchecked (tests/view_xvfb.sh says why).
    if [ -n "${ASAN_OPTIONS:-}" ]; then
        ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"
        export ASAN_OPTIONS
    fi
    xvfb-run -a -s "-screen 0 640x480x24 -nolisten tcp" \
        sh "$0" --view "$view" "$scenes" "$deep/saved frames"
    [ -s "$deep/saved frames/frame-0001.png" ] || fail "view: no saved frame"
    echo "sgapi-view: scene file, title and saved frame in the deep folder"
else
    echo "sgapi-view not built: skipped"
fi
