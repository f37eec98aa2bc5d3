#!/bin/sh
# Time per frame and peak memory against triangle count and against pixel count.
#   tools/scale-plot.sh [BUILD_DIR] [OUT.png]      (defaults: build, docs/images/scale.png)
# Renders, each in its own process so that its peak resident set is its own:
#   - triangles: the scenes of scenes/scale.json at 1024 x 1024 (scale_100k, scale_1m,
#     scale_10m) and scale_100m, made here from scale_10m: fifty of its 2 M-triangle spheres at
#     half size, ten by five (SCALE_100M=0 leaves it out; it is no scene file, so that no test
#     renders it);
#   - pixels: scale_16k (one 262 k-triangle sphere) at 1024^2, 4096^2 and 16384^2, the scene
#     rewritten to each size (jq).
# Each scene is rendered from a file of its own (sgapi-render loads every scene of a file).
# Each with sgapi-render --frames FRAMES (default 6) --frame-times --threads THREADS (default 2)
# --no-write under /usr/bin/time -v: the first frame (it grows the device's storage), the median
# of the others (steady) and the process's peak resident set (scene loading and geometry
# included); ROUNDS times (default 3), keeping the median first and steady frame and the largest
# peak (a busy moment of the machine moves one round, not the row). BIN_MEMORY sets --bin-memory (default 0: the device's default). Writes OUT.csv
# beside OUT.png and plots both series with gnuplot.
set -eu
build=${1:-build}
png=${2:-docs/images/scale.png}
csv=${png%.png}.csv
frames=${FRAMES:-6}
rounds=${ROUNDS:-3}
threads=${THREADS:-2}
bin_memory=${BIN_MEMORY:-0}
render=$build/apps/sgapi-render
scenes=$(dirname "$0")/../scenes/scale.json
[ -x "$render" ] || { echo "scale-plot: no $render (build first)" >&2; exit 1; }
command -v jq >/dev/null || { echo "scale-plot: needs jq" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "scale-plot: needs /usr/bin/time (package time)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The scenes, each alone in a file of its own (sgapi-render loads every scene of a file, --scene
# or not): "series scene" lines in $tmp/list, the file $tmp/<scene>.json.
add() {
    echo "$1 $2" >>"$tmp/list"
    cat >"$tmp/$2.json"
}
: >"$tmp/list"
for s in scale_100k scale_1m scale_10m; do
    jq --arg s "$s" '.scenes |= map(select(.name == $s))' "$scenes" | add triangles "$s"
done
if [ "${SCALE_100M:-1}" = 1 ]; then
    jq '(.scenes[] | select(.name == "scale_10m")) as $s | .scenes = [$s | .name = "scale_100m" |
        .draws = [range(0; 5) as $j | range(0; 10) as $i | $s.draws[0] | .worldView =
        [0.5, 0, 0, -1.35 + 0.3 * $i, 0, 0.5, 0, -0.6 + 0.3 * $j, 0, 0, 0.5, -3, 0, 0, 0, 1]]]' \
        "$scenes" | add triangles scale_100m
fi
for n in 1024 4096 16384; do
    jq --argjson n "$n" '.scenes |= map(select(.name == "scale_16k") | .width = $n |
        .height = $n | .name = "scale_px_\($n)")' "$scenes" | add pixels "scale_px_$n"
done

# Renders scene $1 once; appends "first steady peak" to $tmp/<scene>.txt.
run() {
    /usr/bin/time -v "$render" "$tmp/$1.json" -o "$tmp/img" --frames "$frames" --frame-times \
        --threads "$threads" --bin-memory "$bin_memory" --no-write >/dev/null 2>"$tmp/err" ||
        { cat "$tmp/err" >&2; exit 1; }
    awk '
        function median(a, n,  i, j, x) {
            for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
                if (a[j] < a[i]) { x = a[i]; a[i] = a[j]; a[j] = x }
            return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
        }
        / frame [0-9]+: / { n++; t[n] = $(NF - 1) }
        /Maximum resident set size/ { rss = $NF / 1024 }
        END { for (i = 2; i <= n; i++) s[i - 1] = t[i]; print t[1], median(s, n - 1), rss }
    ' "$tmp/err" >>"$tmp/$1.txt"
}

# Rounds outside, scenes inside: a busy moment of the machine moves one round of a scene.
r=0
while [ $r -lt "$rounds" ]; do
    while read -r series scene; do run "$scene"; done <"$tmp/list"
    r=$((r + 1))
done

# A row per scene: the median first and steady frame over the rounds, the largest peak.
echo "series,scene,pixels,triangles,first_ms,steady_ms,peak_rss_mib" >"$csv"
while read -r series scene; do
    f=$tmp/$scene.json
    tris=$(jq '[.scenes[0].draws[].mesh | 2 * .segments * .rings] | add' "$f")
    pixels=$(jq '(.scenes[0].width // .width) * (.scenes[0].height // .height)' "$f")
    awk -v series="$series" -v scene="$scene" -v px="$pixels" -v tris="$tris" '
        function median(a, n,  i, j, x) {
            for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
                if (a[j] < a[i]) { x = a[i]; a[i] = a[j]; a[j] = x }
            return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
        }
        { n++; f[n] = $1; s[n] = $2; if ($3 > rss) rss = $3 }
        END {
            printf "%s,%s,%d,%d,%.1f,%.1f,%.0f\n", series, scene, px, tris, median(f, n),
                median(s, n), rss
        }' "$tmp/$scene.txt" | tee -a "$csv"
done <"$tmp/list"

# Two panels, time on the left axis and peak memory on the right, log-log, in sgapi-bench's
# --pareto style.
cat >"$tmp/scale.gp" <<EOF
set terminal png size 1400,600 noenhanced
set output '$png'
set datafile separator ','
set multiplot layout 1,2 title 'sgapi-render, $threads threads: time per frame and peak memory'
set logscale xy
set logscale y2
set grid
set key top left box opaque
set ytics nomirror
set y2tics
set ylabel 'ms per frame (log scale)'
set y2label 'peak resident set, MiB (log scale)'
set xrange [5e4:2e8]
set xlabel 'triangles (1024 x 1024 image, log scale)'
set title 'against triangle count'
plot '$csv' using (strcol(1) eq 'triangles' ? \$4 : NaN):5 with linespoints pt 7 ps 1.5 lt 1 title 'first frame', \
  '' using (strcol(1) eq 'triangles' ? \$4 : NaN):6 with linespoints pt 7 ps 1.5 lt 2 title 'steady frame', \
  '' using (strcol(1) eq 'triangles' ? \$4 : NaN):7 axes x1y2 with linespoints pt 5 ps 1.5 lt 3 dt 2 title 'peak RSS (right)'
set xrange [5e5:5e8]
set xlabel 'pixels (one 262 k-triangle sphere, log scale)'
set title 'against pixel count'
plot '$csv' using (strcol(1) eq 'pixels' ? \$3 : NaN):5 with linespoints pt 7 ps 1.5 lt 1 title 'first frame', \
  '' using (strcol(1) eq 'pixels' ? \$3 : NaN):6 with linespoints pt 7 ps 1.5 lt 2 title 'steady frame', \
  '' using (strcol(1) eq 'pixels' ? \$3 : NaN):7 axes x1y2 with linespoints pt 5 ps 1.5 lt 3 dt 2 title 'peak RSS (right)'
unset multiplot
EOF
if command -v gnuplot >/dev/null; then
    gnuplot "$tmp/scale.gp" && echo "scale-plot: wrote $csv and $png"
else
    echo "scale-plot: gnuplot is not installed: no plot (the figures are in $csv)" >&2
fi
