#!/bin/sh
# sgapi-view driven as a person would, with real X input events (xdotool) in a virtual X server
# (Xvfb): F12 saves frames, and the saved images show that
# - a mouse drag moved the camera (the frame after it differs from the one before);
# - N added a shape (the next frame differs again), Delete removed it while the animation runs
#   (the frame after it is the one before the shape, pixel for pixel);
# - L toggles the wireframe (the frame differs) and back.
#   view_xvfb.sh VIEW_BINARY DIFF_BINARY SCENE_FILE SCENE_NAME WORK_DIR
set -eu
if [ -z "${SGAPI_VIEW_TEST_INNER:-}" ]; then
    # A display of our own: -a takes the first free one.
    SGAPI_VIEW_TEST_INNER=1 exec xvfb-run -a -s "-screen 0 1280x1024x24 -nolisten tcp" \
        sh "$0" "$@"
fi
view=$1
diff=$2
scene=$3
name=$4
work=$5
rm -rf "$work"
mkdir -p "$work"
fail() {
    echo "FAIL: $*"
    [ -f "$work/view.log" ] && cat "$work/view.log"
    exit 1
}

# Under AddressSanitizer (tools/sanitize.sh) the viewer's leaks go unchecked: the D-Bus and X
# libraries SDL loads keep allocations to the end, some in libraries SDL has unloaded by then,
# which no suppression can name. Every other sanitizer check stays on; the loaders and the
# renderer are leak-checked through the other tests.
if [ -n "${ASAN_OPTIONS:-}" ]; then
    ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"
    export ASAN_OPTIONS
fi
"$view" "$scene" --scene "$name" --size 320x240 --threads 1 --save-dir "$work" \
    >"$work/view.log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT

wid=$(timeout 30 xdotool search --sync --name '^sgapi-view' | head -n 1)
[ -n "$wid" ] || fail "no sgapi-view window"
xdotool windowfocus --sync "$wid" || fail "could not focus the sgapi-view window"

# Presses F12 and waits for frame N (written whole: the writer renames a finished file).
shot() {
    xdotool key --clearmodifiers F12
    f=$(printf '%s/frame-%04d.png' "$work" "$1")
    i=0
    while [ ! -f "$f" ]; do
        i=$((i + 1))
        [ $i -lt 300 ] || fail "F12 did not save $f"
        sleep 0.1
    done
}
same() { "$diff" "$work/frame-000$1.png" "$work/frame-000$2.png" --max-over2 0 >/dev/null; }

shot 1
xdotool mousemove --window "$wid" 160 120 mousedown 1
xdotool mousemove --window "$wid" 200 130
xdotool mousemove --window "$wid" 240 140 mouseup 1
# The viewer takes the events on its next frame; F12 after them is handled after them.
shot 2
same 1 2 && fail "the frame did not change after a mouse drag"
xdotool key --clearmodifiers space n
shot 3
same 2 3 && fail "no shape appeared after N"
xdotool key --clearmodifiers Delete
shot 4
same 2 4 || fail "the deleted shape is still drawn (frame 4 differs from frame 2)"
xdotool key --clearmodifiers l
shot 5
same 4 5 && fail "L did not turn the wireframe on"
xdotool key --clearmodifiers l
shot 6
same 4 6 || fail "L did not turn the wireframe off"
xdotool key --clearmodifiers Escape
i=0
while kill -0 $pid 2>/dev/null; do
    i=$((i + 1))
    [ $i -lt 100 ] || fail "Esc did not quit"
    sleep 0.1
done
wait $pid || fail "sgapi-view exited with an error"
echo "sgapi-view: drag, add, delete, wireframe and F12 work"
