#!/bin/sh
# Renders every scene file of scenes/ (but scale.json) and the hard cases with the default
# bin_memory_limit and with limits that flush many times a pass (65536 bytes: a few hundred
# triangles; 1000000: rounds of the parallel front end between flushes), at 1 and 2 threads,
# and requires every image to be identical byte for byte to the default one's.
#   bin_memory_identical.sh RENDER_BINARY SOURCE_DIR WORK_DIR
set -eu
render=$1
src=$2
work=$3
rm -rf "$work"
render_all() { # DIR OPTIONS... (PNG level 0: the pixels are what is compared)
    dir=$1
    shift
    for f in "$src"/scenes/*.json; do
        name=$(basename "$f" .json)
        [ "$name" = scale ] && continue # millions of triangles a scene: for sgapi-bench
        "$render" "$f" -o "$dir/$name" --png-level 0 "$@" >/dev/null
    done
    for f in "$src"/scenes/hard/*.json; do
        "$render" "$f" -o "$dir/hard" --png-level 0 "$@" >/dev/null
    done
}
render_all "$work/default" --threads 1
status=0
for t in 1 2; do
    for limit in 65536 1000000; do
        render_all "$work/$t-$limit" --threads "$t" --bin-memory "$limit"
        for png in "$work/default"/*/*.png; do
            other="$work/$t-$limit/${png#"$work/default"/}"
            if ! cmp -s "$png" "$other"; then
                echo "differs with --threads $t --bin-memory $limit: ${png#"$work/default"/}"
                status=1
            fi
        done
    done
done
[ $status -eq 0 ] && echo "identical images with bin_memory_limit 65536 and 1000000 at 1 and 2 threads"
exit $status
