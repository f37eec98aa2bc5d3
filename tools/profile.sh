#!/bin/sh
# Prints, per scene, where sgapi's work goes: instructions of one frame (callgrind, one thread,
# only inside sgDraw and sgEndRenderPass), grouped by pipeline stage, as a markdown table.
# Instruction counts are repeatable whatever else the machine runs; they are not times (a texel
# gather or a cache miss costs more than an add), so read them next to sgapi-bench's times.
#   tools/profile.sh [BUILD_DIR] SCENES.json...      (default build dir: build)
set -eu
build=build
if [ $# -gt 0 ] && [ -d "$1" ]; then
    build=$1
    shift
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | M instr / frame | front end % | coverage + depth % | shading % | bin start + write % |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for file in "$@"; do
    for scene in $("$build/apps/sgapi-render" "$file" -o "$out/list" | awk '{ print $1 }'); do
        valgrind --tool=callgrind --callgrind-out-file="$out/cg" --toggle-collect=sgDraw \
            --toggle-collect=sgEndRenderPass "$build/apps/sgapi-render" "$file" --scene "$scene" \
            --threads 1 -o "$out/img" >/dev/null 2>&1
        callgrind_annotate --threshold=100 "$out/cg" 2>/dev/null | awk -v scene="$scene" '
            /^ *[0-9,]+ .*:/ && !/PROGRAM TOTALS/ {
                n = $1; gsub(",", "", n); f = $0; sub(/^[^:]*:/, "", f); sub(/ .*/, "", f)
                if (f ~ /^(shade_|sg_shade)/) s += n
                else if (f ~ /^(walk_tiles|accepted_tiles|sg_rast_triangle|vis_|crossed_mask)/) r += n
                else if (f ~ /^(sg_rast_bin|shade_tile|same_id|sg_fb_|sg_tile_|sg_fill_|render_bin|mem(set|cpy|move)|__mem)/) b += n
                else fe += n
                t += n }
            END { if (t == 0) t = 1
                  printf "| %s | %.1f | %.0f | %.0f | %.0f | %.0f |\n", scene, t / 1e6,
                         100 * fe / t, 100 * r / t, 100 * s / t, 100 * b / t }'
    done
done
