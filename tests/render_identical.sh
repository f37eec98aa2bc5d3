#!/bin/sh
# Renders every scene file of scenes/ and the hard cases once for each value of one sgapi-render option
# and requires every image to be identical byte for byte to the first value's (PNG level 0: the
# pixels are what is compared, and compressing them took a third of the time).
#   render_identical.sh RENDER_BINARY SOURCE_DIR WORK_DIR OPTION VALUE...
# --threads 1 2 3 5: bins share no pixels and keep submission order, so the thread count must
# never show in the output. --simd scalar sse2 avx2 avx512 neon: the vector paths compute the same IEEE
# operations in the same order as the scalar reference, and so do the built-in shaders' compilations
# the set picks (baseline, AVX2, AVX-512); a set this CPU does not run is refused at device
# creation and skipped.
set -eu
render=$1
src=$2
work=$3
option=$4
shift 4
rm -rf "$work"
values=
for v in "$@"; do
    if "$render" "$src/scenes/hard/degenerate.json" -o "$work/probe" "$option" "$v" >/dev/null 2>&1; then
        values="$values $v"
    else
        echo "$option $v is not available here: not compared"
    fi
done
first=
for v in $values; do
    [ -z "$first" ] && first=$v
    for f in "$src"/scenes/*.json; do
        name=$(basename "$f" .json)
        [ "$name" = scale ] && continue # millions of triangles a scene: sgapi-bench's, not a test's
        "$render" "$f" -o "$work/$v/$name" "$option" "$v" --png-level 0 >/dev/null
    done
    for f in "$src"/scenes/hard/*.json; do
        "$render" "$f" -o "$work/$v/hard" "$option" "$v" --png-level 0 >/dev/null
    done
    # Shaders (discards, depth written where a fragment stays) and blends at 4 samples too: the
    # multisampled bins' in-place paths.
    for name in shaders transparency; do
        "$render" "$src/scenes/$name.json" -o "$work/$v/${name}_4" "$option" "$v" --samples 4 \
            --png-level 0 >/dev/null
    done
done
status=0
for v in $values; do
    [ "$v" = "$first" ] && continue
    for png in "$work/$first"/*/*.png; do
        other="$work/$v/${png#"$work/$first"/}"
        if ! cmp -s "$png" "$other"; then
            echo "differs with $option $v: ${png#"$work/$first"/}"
            status=1
        fi
    done
done
[ $status -eq 0 ] && echo "identical images with $option$values"
exit $status
