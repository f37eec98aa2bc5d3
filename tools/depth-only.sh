#!/bin/sh
# Compares, per scene at one thread, a depth-only pass with the coverage and depth part of the
# same scene's ordinary pass: a profiling build (SGAPI_STAGE_TIMES, in BUILD_DIR, default
# build-times) adds up each stage; the ordinary pass's coverage + depth is its front end, bin
# start (clears) and visibility; the depth-only pass's time is all of its stages (front end, clear,
# visibility, depth written). Prints a markdown table with their ratio.
#   tools/depth-only.sh [BUILD_DIR] SCENES.json...
set -eu
build=build-times
case ${1:-} in *.json) ;; ?*) build=$1; shift ;; esac
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSGAPI_STAGE_TIMES=ON -DSGAPI_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j --target sgapi-render >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | coverage + depth of the ordinary pass, ms | depth-only pass, ms | ratio |"
echo "| --- | ---: | ---: | ---: |"
for file in "$@"; do
    for scene in $("$build/apps/sgapi-render" "$file" -o "$out/list" 2>/dev/null | awk '{ print $1 }'); do
        # stderr: sgapi stage times, ms per pass (N passes): front-end A bin-start B visibility C ...
        stages() {
            "$build/apps/sgapi-render" "$file" --scene "$scene" --frames 50 --threads 1 \
                -o "$out/img" "$@" 2>&1 >/dev/null | tr '\n' ' '
        }
        ordinary=$(stages | awk '{ for (i = 1; i <= NF; i++) v[$i] = $(i + 1)
            printf "%.3f", v["front-end"] + v["bin-start"] + v["visibility"] }')
        only=$(stages --depth-only | awk '{ for (i = 1; i <= NF; i++) v[$i] = $(i + 1)
            t = v["front-end"] + v["bin-start"] + v["visibility"]
            printf "%.3f", t + v["shading"] + v["bin-write"] }')
        echo "$scene $ordinary $only" | awk '{ printf "| %s | %s | %s | %.2f |\n", $1, $2, $3, $3 / $2 }'
    done
done
