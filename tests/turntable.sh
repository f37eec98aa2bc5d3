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
[ "$(wc -l <"$work/all.out")" -eq 3 ] || fail "not one line per scene: $(cat "$work/all.out")"
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

# ---- the progress bar ----
if command -v script >/dev/null 2>&1; then
    # stderr on a terminal (script's), stdout to a file.
    script -qec "'$render' '$work/tiny.json' -o '$work/tty' --turntable $frames >'$work/tty.out'" \
        "$work/tty.log" >/dev/null
    grep -q "\] 21/21 frames .* fps .* left" "$work/tty.log" || fail "no progress bar on a terminal"
    grep -q "fps" "$work/tty.out" && fail "the progress bar went to stdout"
    [ "$(wc -l <"$work/tty.out")" -eq 3 ] || fail "stdout is not one line per scene"
    script -qec "'$render' '$work/tiny.json' -o '$work/tty' --turntable $frames --quiet \
        >'$work/tty.out'" "$work/quiet.log" >/dev/null
    grep -q "left" "$work/quiet.log" && fail "--quiet drew a progress bar"
    echo "progress bar on a terminal only, not with --quiet"
else
    echo "script(1) is missing: the progress bar on a terminal is not checked"
fi
echo "turntable: all checks passed"
