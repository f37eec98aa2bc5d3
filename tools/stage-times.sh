#!/bin/sh
# Prints, per scene, where one frame's wall time goes at one thread: a profiling build of the
# library (SGAPI_STAGE_TIMES, configured in BUILD_DIR, default build-times) adds up each stage's
# time, and this prints it per frame as a markdown table. The timers themselves cost a few percent.
#   tools/stage-times.sh [BUILD_DIR] SCENES.json...
set -eu
build=build-times
case ${1:-} in *.json) ;; ?*) build=$1; shift ;; esac
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSGAPI_STAGE_TIMES=ON -DSGAPI_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j --target sgapi-render >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | ms / frame | front end | bin start | coverage + depth | shading | bin write |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
for file in "$@"; do
    for scene in $("$build/apps/sgapi-render" "$file" -o "$out/list" 2>/dev/null | awk '{ print $1 }'); do
        # prints: NAME MS ms/frame (median of 50), then on stderr:
        # sgapi stage times, ms per pass (N passes): front-end A bin-start B visibility C ...
        "$build/apps/sgapi-render" "$file" --scene "$scene" --frames 50 --threads 1 \
            -o "$out/img" 2>&1 | tr '\n' ' ' | awk '{
                for (i = 1; i <= NF; i++) v[$i] = $(i + 1)
                printf "| %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, v["front-end"],
                       v["bin-start"], v["visibility"], v["shading"], v["bin-write"] }'
    done
done
