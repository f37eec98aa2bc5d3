#!/bin/sh
# Compares two builds of sgapi-render scene by scene: runs them in turn, A B A B ..., ROUNDS times
# (default 6), each rendering every scene FRAMES times (default 40) at THREADS threads (default
# 1), and prints per scene the median over the rounds of each build's median time per frame and
# their ratio B / A. Taking the two in turn keeps a drift of the machine's speed out of the ratio.
#   tools/ab-render.sh BUILD_A BUILD_B SCENES.json... [-- EXTRA sgapi-render OPTIONS]
set -eu
a=${1:?usage: tools/ab-render.sh BUILD_A BUILD_B SCENES.json... [-- OPTIONS]}
b=${2:?usage: tools/ab-render.sh BUILD_A BUILD_B SCENES.json... [-- OPTIONS]}
shift 2
files=
while [ $# -gt 0 ] && [ "$1" != -- ]; do
    files="$files $1"
    shift
done
[ "${1:-}" = -- ] && shift
rounds=${ROUNDS:-6}
frames=${FRAMES:-40}
threads=${THREADS:-1}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
i=0
while [ $i -lt "$rounds" ]; do
    for side in A B; do
        dir=$a
        [ $side = B ] && dir=$b
        # shellcheck disable=SC2086
        "$dir/apps/sgapi-render" $files -o "$out/img" --frames "$frames" --threads "$threads" "$@" |
            awk -v s=$side '{ print s, $1, $2 }' >>"$out/times.txt"
    done
    i=$((i + 1))
done
echo "| scene | A ms | B ms | B / A |"
echo "| --- | ---: | ---: | ---: |"
sort -k2,2 -k1,1 -k3,3g "$out/times.txt" | awk '
    function median(arr, n) { return n % 2 ? arr[(n + 1) / 2] : (arr[n / 2] + arr[n / 2 + 1]) / 2 }
    { key = $2; if (!(key in seen)) { seen[key] = 1; order[++nk] = key }
      n[$1, key]++; v[$1, key, n[$1, key]] = $3 }
    END {
        for (k = 1; k <= nk; k++) {
            key = order[k]
            for (side = 0; side < 2; side++) {
                s = side ? "B" : "A"
                delete arr
                for (i = 1; i <= n[s, key]; i++) arr[i] = v[s, key, i]
                m[s] = median(arr, n[s, key])
            }
            printf "| %s | %.3f | %.3f | %.3f |\n", key, m["A"], m["B"], m["B"] / m["A"]
        }
    }'
