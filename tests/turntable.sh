#!/bin/sh
# sgapi-render --turntable, --spin and --shard on small scenes (tests/tiny_scenes.sh):
# - frame names and counts; frame 0 is the plain render of the scene, byte for byte; the scene
#   turns (the next frame differs); --spin turns one draw;
# - every shard of N = 1, 2, 3, 7 run apart: each frame (and, without --turntable, each scene) is
#   written by exactly one shard, byte-identical to the unsharded run's;
# - bad input (--shard 3/3, --shard 1/0, --turntable 0, an unwritable DIR, an unknown video format,
#   and other options that do not go together): exit 2 and nothing written;
# - the progress bar: on stderr when it is a terminal (script(1) gives one), never on stdout,
#   not with --quiet, and nothing on stderr when it is not a terminal.
#   turntable.sh RENDER_BINARY SOURCE_DIR WORK_DIR
set -eu
render=$1
src=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
sh "$src/tests/tiny_scenes.sh" "$work/tiny.json" "$src"
scenes="lit_shadow textured empty"
frames=7
fail() {
    echo "FAIL: $*"
    exit 1
}

# ---- frames, frame 0, turning ----
"$render" "$work/tiny.json" -o "$work/plain" --png-level 0 >/dev/null
"$render" "$work/tiny.json" -o "$work/all" --turntable $frames >"$work/all.out" 2>"$work/all.err"
[ -s "$work/all.err" ] && fail "stderr is not a terminal, yet it got: $(cat "$work/all.err")"
for s in $scenes; do
    n=$(ls "$work/all/$s" | wc -l)
    [ "$n" -eq $frames ] || fail "$s: $n frames, not $frames"
    [ -f "$work/all/$s/0006.png" ] || fail "$s: no 0006.png"
    cmp -s "$work/plain/$s.png" "$work/all/$s/0000.png" || fail "$s: frame 0 is not the plain render"
    grep -q "^$s  *[0-9.]* frames/s ($frames frames in " "$work/all.out" || fail "$s: no line"
done
# Stdout: a line per frame as it is on disk, a line per scene, the summary last.
[ "$(grep -c '^frame [a-z_]*/000[0-6]\.png [0-9.]* ms$' "$work/all.out")" -eq 21 ] ||
    fail "not one line per frame: $(cat "$work/all.out")"
[ "$(grep -c 'frames/s' "$work/all.out")" -eq 3 ] || fail "not one line per scene"
tail -n 1 "$work/all.out" | grep -q '^done: 21 of 21 frames on disk (21 rendered, 0 already there) in ' ||
    fail "no summary last: $(tail -n 1 "$work/all.out")"
[ "$(wc -l <"$work/all.out")" -eq 25 ] || fail "other lines: $(cat "$work/all.out")"
cmp -s "$work/all/lit_shadow/0000.png" "$work/all/lit_shadow/0001.png" && fail "lit_shadow does not turn"
cmp -s "$work/all/empty/0000.png" "$work/all/empty/0003.png" || fail "a scene without draws changed"
# A whole turn in four frames: frame 2 is half a turn, the image of a scene mirrored.
"$render" "$work/tiny.json" -o "$work/spin" --turntable 4 --spin 1 --scene lit_shadow >/dev/null
cmp -s "$work/spin/lit_shadow/0000.png" "$work/plain/lit_shadow.png" || fail "--spin: frame 0"
cmp -s "$work/spin/lit_shadow/0001.png" "$work/all/lit_shadow/0001.png" && fail "--spin orbits"
cmp -s "$work/spin/lit_shadow/0001.png" "$work/spin/lit_shadow/0000.png" && fail "--spin: no turn"
# --up: about the floor's up (draw 0), frame 0 is still the scene as written, the rest differ.
"$render" "$work/tiny.json" -o "$work/up" --turntable 4 --up 0 --scene lit_shadow >/dev/null
cmp -s "$work/up/lit_shadow/0000.png" "$work/plain/lit_shadow.png" || fail "--up: frame 0"
cmp -s "$work/up/lit_shadow/0001.png" "$work/up/lit_shadow/0000.png" && fail "--up: no turn"
# More than 10000 frames need a fifth digit (one shard of many renders a frame of each name).
"$render" "$work/tiny.json" -o "$work/long" --turntable 10001 --scene empty --shard 10000/10001 \
    >/dev/null
[ -f "$work/long/empty/10000.png" ] || fail "frame 10000 of 10001 is not 10000.png"

# ---- shards ----
# Every shard into a folder of its own: each file must be in exactly one of them and equal the
# unsharded run's; with --turntable the frames are counted across scenes, without it the scenes.
check_shards() { # N UNSHARDED_DIR [options]
    n=$1
    whole=$2
    shift 2
    i=0
    while [ $i -lt "$n" ]; do
        "$render" "$work/tiny.json" -o "$work/shards$n/$i" --shard $i/"$n" "$@" >/dev/null
        i=$((i + 1))
    done
    total=0
    for f in $(cd "$whole" && find . -name '*.png' | sort); do
        copies=0
        i=0
        while [ $i -lt "$n" ]; do
            if [ -f "$work/shards$n/$i/$f" ]; then
                cmp -s "$whole/$f" "$work/shards$n/$i/$f" || fail "N=$n: shard $i's $f differs"
                copies=$((copies + 1))
            fi
            i=$((i + 1))
        done
        [ $copies -eq 1 ] || fail "N=$n: $f written by $copies shards"
        total=$((total + 1))
    done
    written=$(find "$work/shards$n" -name '*.png' | wc -l)
    [ "$written" -eq "$total" ] || fail "N=$n: the shards wrote $written files, the whole run $total"
    rm -rf "$work/shards$n"
}
for n in 1 2 3 7; do
    check_shards $n "$work/all" --turntable $frames
    check_shards $n "$work/plain" --png-level 0
done
echo "shards of 1, 2, 3, 7 give the unsharded files"

# ---- --resume and --progress-file ----
# A whole run resumed renders nothing; frames deleted, cut short or of another size are rendered
# again (the damaged ones named on stderr), and the folder ends as the uninterrupted run's.
cp -r "$work/all" "$work/res"
"$render" "$work/tiny.json" -o "$work/res" --turntable $frames --resume --progress-file \
    "$work/res.jsonl" >"$work/res.out" 2>"$work/res.err"
tail -n 1 "$work/res.out" | grep -q '^done: 21 of 21 frames on disk (0 rendered, 21 already there)' ||
    fail "--resume of a whole run: $(tail -n 1 "$work/res.out")"
grep -q '^frame ' "$work/res.out" && fail "--resume of a whole run rendered $(grep '^frame ' "$work/res.out")"
[ -s "$work/res.err" ] && fail "--resume of a whole run said $(cat "$work/res.err")"
rm "$work/res/textured/0003.png"
head -c 200 "$work/all/lit_shadow/0005.png" >"$work/res/lit_shadow/0005.png"
cp "$work/all/textured/0001.png" "$work/res/lit_shadow/0002.png" # another scene's size
printf 'not a png' >"$work/res/empty/0006.png"
"$render" "$work/tiny.json" -o "$work/res" --turntable $frames --resume --progress-file \
    "$work/res.jsonl" >"$work/res.out" 2>"$work/res.err"
[ "$(grep -c '^frame ' "$work/res.out")" -eq 4 ] || fail "--resume rendered: $(cat "$work/res.out")"
for f in textured/0003 lit_shadow/0005 lit_shadow/0002 empty/0006; do
    grep -q "^frame $f.png " "$work/res.out" || fail "--resume did not render $f"
done
grep -q "lit_shadow/0005.png ends inside its chunk 'IDAT' (200 bytes): rendering it again" \
    "$work/res.err" || fail "a frame cut short is not named: $(cat "$work/res.err")"
grep -q "lit_shadow/0002.png is [0-9]*x[0-9]*, not [0-9]*x[0-9]*: rendering it again" \
    "$work/res.err" || fail "a frame of another size is not named: $(cat "$work/res.err")"
grep -q "empty/0006.png is too short for a PNG file" "$work/res.err" || fail "a bad file: $(cat "$work/res.err")"
[ "$(wc -l <"$work/res.err")" -eq 3 ] || fail "--resume said more: $(cat "$work/res.err")"
diff -r "$work/all" "$work/res" >/dev/null || fail "--resume did not end with the whole run's files"
# The progress file: both runs appended, each from "start" to "end".
python3 - "$work/res.jsonl" <<'PY' || fail "the progress file"
import json, sys
events = [json.loads(line) for line in open(sys.argv[1])]
kinds = [e["event"] for e in events]
assert kinds.count("start") == 2 and kinds.count("end") == 2, kinds
assert kinds.count("skipped") == 21 + 17 and kinds.count("done") == 4, kinds
assert kinds.count("redo") == 3, kinds
assert events[-1] == {**events[-1], "status": 0, "items": 21, "rendered": 4, "skipped": 17, "not_done": 0}
assert all(e["finished"] <= e["items"] for e in events if "finished" in e)
PY
# Still images: --resume skips the images on disk.
cp -r "$work/plain" "$work/res_plain"
rm "$work/res_plain/textured.png"
"$render" "$work/tiny.json" -o "$work/res_plain" --png-level 0 --resume >"$work/res.out"
[ "$(grep -c 'ms/frame' "$work/res.out")" -eq 1 ] && grep -q '^textured ' "$work/res.out" ||
    fail "--resume of still images: $(cat "$work/res.out")"
tail -n 1 "$work/res.out" | grep -q '^done: 3 of 3 images on disk (1 rendered, 2 already there)' ||
    fail "--resume of still images: $(tail -n 1 "$work/res.out")"
diff -r "$work/plain" "$work/res_plain" >/dev/null || fail "--resume of still images differs"
echo "--resume renders only what is missing or damaged and ends byte-identical"

# ---- bad input: exit 2, nothing written ----
touch "$work/file"
bad() { # DIR options...
    dir=$1
    shift
    set +e
    "$render" "$work/tiny.json" -o "$dir" "$@" >"$work/bad.out" 2>"$work/bad.err"
    rc=$?
    set -e
    [ $rc -eq 2 ] || fail "$*: exit $rc, not 2"
    [ -s "$work/bad.err" ] || fail "$*: no message"
    [ -s "$work/bad.out" ] && fail "$*: printed $(cat "$work/bad.out")"
    [ -e "$work/bad" ] && fail "$*: wrote $work/bad"
    echo "exit 2: $* ($(head -n 1 "$work/bad.err"))"
}
bad "$work/bad" --turntable 3 --shard 3/3
bad "$work/bad" --turntable 3 --shard 1/0
bad "$work/bad" --shard 1/
bad "$work/bad" --turntable 0
bad "$work/file/out" --turntable 3
bad "$work/bad" --turntable 3 --video webm
bad "$work/bad" --turntable 3 --video gif,
bad "$work/bad" --turntable 3 --video gif --shard 0/2
bad "$work/bad" --video gif
bad "$work/bad" --spin 0
bad "$work/bad" --turntable 3 --spin 5
bad "$work/bad" --turntable 3 --up 0
bad "$work/bad" --up 0 --scene lit_shadow
bad "$work/bad" --turntable 3 --frames 2
bad "$work/bad" --turntable 3 --png-level 13
bad "$work/bad" --turntable 3 --video gif --assemble --resume
bad "$work/bad" --resume --no-write
bad "$work/bad" --turntable 3 --progress-file "$work/file/p.jsonl"

# ---- the progress bar ----
if command -v script >/dev/null 2>&1; then
    # stderr on a terminal (script's), stdout to a file.
    script -qec "'$render' '$work/tiny.json' -o '$work/tty' --turntable $frames >'$work/tty.out'" \
        "$work/tty.log" >/dev/null
    grep -q "\] 21/21 frames .* fps .* left" "$work/tty.log" || fail "no progress bar on a terminal"
    grep -q "fps" "$work/tty.out" && fail "the progress bar went to stdout"
    [ "$(grep -c frames/s "$work/tty.out")" -eq 3 ] || fail "stdout is not one line per scene"
    [ "$(grep -c '^frame ' "$work/tty.out")" -eq 21 ] || fail "stdout is not one line per frame"
    script -qec "'$render' '$work/tiny.json' -o '$work/tty' --turntable $frames --quiet \
        >'$work/tty.out'" "$work/quiet.log" >/dev/null
    grep -q "left" "$work/quiet.log" && fail "--quiet drew a progress bar"
    echo "progress bar on a terminal only, not with --quiet"
else
    echo "script(1) is missing: the progress bar on a terminal is not checked"
fi
echo "turntable: all checks passed"
