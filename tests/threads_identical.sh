#!/bin/sh
# Renders the default scenes and the hard cases with 1, 2, 3 and 5 threads and requires the
# images to be identical byte for byte: bins share no pixels and keep submission order, so the
# thread count must never show in the output.
#   threads_identical.sh RENDER_BINARY SOURCE_DIR WORK_DIR
set -eu
render=$1
src=$2
work=$3
rm -rf "$work"
for t in 1 2 3 5; do
    "$render" "$src/scenes/default.json" -o "$work/$t/default" --threads "$t" >/dev/null
    for f in "$src"/scenes/hard/*.json; do
        "$render" "$f" -o "$work/$t/hard" --threads "$t" >/dev/null
    done
done
status=0
for t in 2 3 5; do
    for png in "$work"/1/*/*.png; do
        other="$work/$t/${png#"$work"/1/}"
        if ! cmp -s "$png" "$other"; then
            echo "differs with $t threads: ${png#"$work"/1/}"
            status=1
        fi
    done
done
[ $status -eq 0 ] && echo "identical images with 1, 2, 3 and 5 threads"
exit $status
