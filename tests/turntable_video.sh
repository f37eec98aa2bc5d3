#!/bin/sh
# sgapi-render --video on small scenes (tests/tiny_scenes.sh), through ffmpeg (the set-up installs
# it; without it this test fails):
# - --video gif,mp4 writes DIR/<scene>.gif and .mp4 of every frame: H.264 in yuv420p at the
#   frames' size (one pixel less on an odd side), a GIF; --video-width scales both;
# - the final step of a sharded run: shards without --video, then --assemble, gives the same GIF
#   as one run; a missing frame is an error naming it;
# - without ffmpeg on PATH: a clear error and exit 2 before anything is rendered.
#   turntable_video.sh RENDER_BINARY SOURCE_DIR WORK_DIR
set -eu
render=$1
src=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
sh "$src/tests/tiny_scenes.sh" "$work/tiny.json" "$src"
fail() {
    echo "FAIL: $*"
    exit 1
}
command -v ffprobe >/dev/null 2>&1 || fail "ffmpeg is not installed (tools/install-deps.sh)"
# codec,width,height,pix_fmt,frames of a video's first stream.
probe() {
    ffprobe -v error -count_frames -select_streams v:0 \
        -show_entries stream=codec_name,width,height,pix_fmt,nb_read_frames -of csv=p=0 "$1"
}

"$render" "$work/tiny.json" -o "$work/one" --turntable 6 --video gif,mp4 --fps 12 >"$work/one.out"
[ "$(probe "$work/one/lit_shadow.mp4")" = "h264,48,36,yuv420p,6" ] ||
    fail "lit_shadow.mp4: $(probe "$work/one/lit_shadow.mp4")"
[ "$(probe "$work/one/textured.mp4")" = "h264,32,24,yuv420p,6" ] ||
    fail "textured.mp4 (33x25 frames): $(probe "$work/one/textured.mp4")"
case "$(probe "$work/one/lit_shadow.gif")" in
gif,48,36,*,6) ;;
*) fail "lit_shadow.gif: $(probe "$work/one/lit_shadow.gif")" ;;
esac
grep -q "^lit_shadow  *$work/one/lit_shadow.gif$" "$work/one.out" || fail "no line for the GIF"
"$render" "$work/tiny.json" -o "$work/small" --turntable 6 --video gif,mp4 --video-width 24 \
    --scene lit_shadow >/dev/null
[ "$(probe "$work/small/lit_shadow.mp4")" = "h264,24,18,yuv420p,6" ] ||
    fail "--video-width 24: $(probe "$work/small/lit_shadow.mp4")"
case "$(probe "$work/small/lit_shadow.gif")" in
gif,24,18,*,6) ;;
*) fail "--video-width 24: $(probe "$work/small/lit_shadow.gif")" ;;
esac
echo "GIF and MP4 of every frame, at the frames' size or scaled"

# The final step of a job array: every shard, then --assemble with the same arguments.
for i in 0 1 2; do
    "$render" "$work/tiny.json" -o "$work/sharded" --turntable 6 --shard $i/3 >/dev/null
done
"$render" "$work/tiny.json" -o "$work/sharded" --turntable 6 --video gif,mp4 --fps 12 \
    --assemble >/dev/null
for s in lit_shadow textured empty; do
    cmp -s "$work/one/$s.gif" "$work/sharded/$s.gif" || fail "$s.gif: assembled differs"
    [ "$(probe "$work/sharded/$s.mp4")" = "$(probe "$work/one/$s.mp4")" ] || fail "$s.mp4"
done
rm "$work/sharded/textured/0004.png"
set +e
"$render" "$work/tiny.json" -o "$work/sharded" --turntable 6 --video gif --assemble \
    >/dev/null 2>"$work/missing.err"
rc=$?
set -e
[ $rc -eq 1 ] || fail "--assemble with a frame missing: exit $rc"
grep -q "textured/0004.png is missing" "$work/missing.err" || fail "$(cat "$work/missing.err")"
echo "--assemble after the shards gives the same videos; a missing frame is named"

# No ffmpeg: exit 2, nothing rendered.
set +e
PATH=/nonexistent "$render" "$work/tiny.json" -o "$work/noffmpeg" --turntable 6 --video mp4 \
    >/dev/null 2>"$work/noffmpeg.err"
rc=$?
set -e
[ $rc -eq 2 ] || fail "without ffmpeg: exit $rc, not 2"
grep -q "ffmpeg" "$work/noffmpeg.err" || fail "without ffmpeg: $(cat "$work/noffmpeg.err")"
[ -e "$work/noffmpeg" ] && fail "without ffmpeg: rendered anyway"
echo "without ffmpeg: $(cat "$work/noffmpeg.err")"
echo "turntable_video: all checks passed"
