#!/bin/sh
# What writing the regression report and the JUnit file adds to a comparison run: runs
#   sgapi-render SCENES -o OUT --compare GOLDEN                      (A)
#   sgapi-render SCENES -o OUT --compare GOLDEN --junit J --report R (B)
# in turn, A B A B ..., ROUNDS times each (alternating, so that a busy machine slows both alike),
# and prints the median wall time of each, the difference in % of A, and the size of the report
# folder against the images it shows.
#   tools/report-overhead.sh BUILD_DIR GOLDEN ROUNDS SCENE.json...
set -eu
build=$1
golden=$2
rounds=$3
shift 3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
render=$build/apps/sgapi-render
now() { date +%s%N; }
i=0
while [ $i -lt "$rounds" ]; do
    for v in A B; do
        rm -rf "$out/report" "$out/img"
        extra=
        [ $v = B ] && extra="--junit $out/junit.xml --report $out/report"
        t0=$(now)
        # shellcheck disable=SC2086
        "$render" "$@" -o "$out/img" --compare "$golden" $extra >/dev/null 2>&1 || [ $? -eq 1 ]
        t1=$(now)
        echo $(((t1 - t0) / 1000)) >>"$out/$v.us"
    done
    i=$((i + 1))
done
median() { sort -n "$1" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
a=$(median "$out/A.us")
b=$(median "$out/B.us")
images=$(du -sb "$out/report/img" | cut -f1)
total=$(du -sb "$out/report" | cut -f1)
awk -v a="$a" -v b="$b" -v n="$rounds" -v img="$images" -v tot="$total" 'BEGIN {
    printf "without --report/--junit: %.1f ms (median of %d)\n", a / 1000, n
    printf "with --report and --junit: %.1f ms (median of %d)\n", b / 1000, n
    printf "overhead: %+.1f %%\n", 100 * (b - a) / a
    printf "report folder: %d bytes, its images %d bytes: %.3f x\n", tot, img, tot / img }'
