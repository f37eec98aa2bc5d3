#!/bin/sh
# Prints, per scene, where one frame's wall time goes at one thread: a profiling build of the
# library (SGAPI_STAGE_TIMES, configured in BUILD_DIR, default build-times) adds up each stage's
# time, and this prints it per frame as a markdown table. The timers themselves cost a few percent.
#   tools/stage-times.sh [BUILD_DIR] SCENES.json...
# With --depth-only, compares instead each scene's pass rendered without its colour target
# (sgapi-render --depth-only: the whole depth-only pass, front end, clear, visibility and the
# depth written) with the coverage and depth part of its ordinary pass (front end, clears and
# visibility), and prints their ratio.
#   tools/stage-times.sh --depth-only [BUILD_DIR] SCENES.json...
set -eu
compare=
[ "${1:-}" = --depth-only ] && compare=1 && shift
build=build-times
case ${1:-} in *.json) ;; ?*) build=$1; shift ;; esac
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSGAPI_STAGE_TIMES=ON -DSGAPI_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j --target sgapi-render >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# One scene's stage times per pass (sgapi-render prints them on stderr as: sgapi stage times, ms
# per pass (N passes): front-end A bin-start B visibility C shading D bin-write E), with the line
# before them: NAME MS ms/frame (median of 50).
stages() { # file scene [sgapi-render options]
    f=$1 s=$2
    shift 2
    "$build/apps/sgapi-render" "$f" --scene "$s" --frames 50 --threads 1 -o "$out/img" "$@" 2>&1 |
        grep -v '^sgapi-render: warning:' | tr '\n' ' ' # a scene file's warnings are not figures
}
if [ -n "$compare" ]; then
    echo "| scene | coverage + depth of the ordinary pass, ms | depth-only pass, ms | ratio |"
    echo "| --- | ---: | ---: | ---: |"
else
    echo "| scene | ms / frame | front end | bin start | coverage + depth | shading | bin write |"
    echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
fi
for file in "$@"; do
    for scene in $("$build/apps/sgapi-render" "$file" -o "$out/list" 2>/dev/null | awk '{ print $1 }'); do
        if [ -z "$compare" ]; then
            stages "$file" "$scene" | awk '{
                for (i = 1; i <= NF; i++) v[$i] = $(i + 1)
                printf "| %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, v["front-end"],
                       v["bin-start"], v["visibility"], v["shading"], v["bin-write"] }'
            continue
        fi
        { stages "$file" "$scene"; echo; stages "$file" "$scene" --depth-only; echo; } | awk '{
            for (i = 1; i <= NF; i++) v[$i] = $(i + 1)
            t[NR] = v["front-end"] + v["bin-start"] + v["visibility"]
            if (NR == 2) t[2] += v["shading"] + v["bin-write"]
            name = $1 }
            END { printf "| %s | %.3f | %.3f | %.2f |\n", name, t[1], t[2], t[2] / t[1] }'
    done
done
