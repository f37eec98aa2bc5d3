#!/bin/sh
# Makes the speed tables of docs/performance.md ("Today") in one run: for each instruction set of
# sgapi's that this CPU has, sgapi-bench over every benchmark scene against lavapipe (same run,
# medians of FRAMES frames and ROUNDS rounds), printed as Markdown under a line that names the
# command, the commit, the date and the machine; then the summary table of all sets.
#   tools/perf-tables.sh [BUILD] [SET...]   (default: build, every set: avx512 avx2 sse2 scalar)
# The gapi-task suite is included when it sits beside the checkout (../shared/gapi-task).
set -eu
cd "$(dirname "$0")/.."
build=${1:-build}
[ $# -gt 0 ] && shift
sets=${*:-avx512 avx2 sse2 scalar}
frames=${FRAMES:-40}
rounds=${ROUNDS:-3}
bench="$build/apps/sgapi-bench"
[ -x "$bench" ] || { echo "perf-tables.sh: $bench is missing (make build)" >&2; exit 2; }

files="scenes/default.json"
[ -f ../shared/gapi-task/scenes.json ] && files="$files ../shared/gapi-task/scenes.json"
files="$files scenes/transparency.json scenes/lighting.json scenes/shadows.json scenes/lines.json"
files="$files scenes/shapes.json"

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD 2>/dev/null || commit="$commit (with uncommitted changes)"
cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -n 1)
cores=$(nproc)
day=$(date -u +%Y-%m-%d)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

summary="$out/summary.md"
: >"$summary"
for set in $sets; do
    # A set this CPU lacks is refused by the bench (exit 2): skipped, and said so.
    # shellcheck disable=SC2086
    if ! "$bench" $files --frames "$frames" --rounds "$rounds" --simd "$set" >"$out/$set.md" \
        2>"$out/$set.err"; then
        echo "perf-tables.sh: --simd $set: $(tail -n 1 "$out/$set.err")" >&2
        continue
    fi
    case $set in
    avx512) title=AVX-512 ;;
    avx2) title=AVX2 ;;
    sse2) title=SSE2 ;;
    scalar) title="Scalar (the portable reference)" ;;
    *) title=$set ;;
    esac
    echo "### $title"
    echo
    echo "Made by \`$bench $files --frames $frames --rounds $rounds --simd $set\` on commit"
    echo "$commit, $day, $cores cores of $cpu:"
    echo
    # The bench's own closing lines (the set, the rounds) are said in the line above.
    grep -v -e '^sgapi-bench:' -e "^sgapi's instruction set:" -e '^each time:' "$out/$set.md"
    echo
    # The summary row: geometric means and the largest ratio at each thread count.
    awk -v set="$title" -v day="$day" -v commit="$commit" -F'|' '
        /^\|/ && NF >= 9 && $2 !~ /^ *(scene|-+) *$/ {
            r1 = $7 + 0; r2 = $8 + 0; name = $2; gsub(/^ +| +$/, "", name)
            if (r1 > m1) { m1 = r1; n1 = name } if (r2 > m2) { m2 = r2; n2 = name } }
        /geometric mean/ { g = $0 }
        END {
            gsub(/,/, "", g); n = split(g, w, " "); g1 = w[n - 2]; g2 = w[n]
            printf "| %s | %s | %s | %.2f (`%s`) | %.2f (`%s`) | %s, %s |\n", set, g1, g2, m1, n1, m2, n2, commit, day
        }' "$out/$set.md" >>"$summary"
done
echo "### Summary"
echo
echo "| instruction set | sgapi / lavapipe, 1 thread | 2 threads | largest, 1 thread | largest, 2 threads | made on |"
echo "| --- | ---: | ---: | ---: | ---: | --- |"
cat "$summary"
