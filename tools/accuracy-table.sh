#!/bin/sh
# Prints the markdown table of sgapi against lavapipe for the project's scene files (the default
# scenes, then one file per feature), the hard cases and,
# when it sits beside the checkout, the gapi-task suite: each renderer's time per frame (median of 5) next to
# the error figures of sgapi's image against lavapipe's.
#   tools/accuracy-table.sh [BUILD_DIR]      (default: build; run `make build` first)
set -eu
build=${1:-build}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "| suite | scene | sgapi ms | lavapipe ms | PSNR dB | % > 2/255 | % > 8/255 | max err | coverage % |"
echo "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
table() { # suite scenes.json
    "$build/apps/sgapi-ref" "$2" -o "$out/$1-ref" --frames 5 >"$out/$1-ref.txt"
    "$build/apps/sgapi-render" "$2" -o "$out/$1" --frames 5 --compare "$out/$1-ref" \
        --thresholds golden/thresholds.csv >"$out/$1.txt" || [ $? -eq 1 ]
    # sgapi-render --compare prints per scene: NAME MS ms/frame (median of 5) psnr P dB >2/255 A %
    # >8/255 B % max M coverage C %; then a summary line (skipped). Exit 1, a scene past its
    # target (named on stderr), still gives the table its figures.
    awk -v suite="$1" 'NR == FNR { ref[$1] = $2; next }
        /ms\/frame/ { for (i = 1; i <= NF; i++) v[$i] = $(i + 1)
          printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", suite, $1, $2, ref[$1],
                 v["psnr"], v[">2/255"], v[">8/255"], v["max"], v["coverage"] }' \
        "$out/$1-ref.txt" "$out/$1.txt"
}
table default scenes/default.json
for f in scenes/*.json; do
    name=$(basename "$f" .json)
    [ "$name" = default ] || [ "$name" = scale ] || table "$name" "$f"
done
# The hard cases: each file alone; where a reference twin exists, lavapipe renders the twin.
for f in scenes/hard/*.json; do
    case $f in *.reference.json) continue ;; esac
    ref=${f%.json}.reference.json
    [ -f "$ref" ] || ref=$f
    "$build/apps/sgapi-ref" "$ref" -o "$out/hard-ref" --frames 5 >>"$out/hard-ref.txt"
    "$build/apps/sgapi-render" "$f" -o "$out/hard" --frames 5 --compare "$out/hard-ref" \
        --thresholds golden/thresholds.csv >>"$out/hard.txt" || [ $? -eq 1 ]
done
awk 'NR == FNR { ref[$1] = $2; next }
    /ms\/frame/ { for (i = 1; i <= NF; i++) v[$i] = $(i + 1)
      printf "| hard | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, ref[$1],
             v["psnr"], v[">2/255"], v[">8/255"], v["max"], v["coverage"] }' \
    "$out/hard-ref.txt" "$out/hard.txt"
if [ -f ../shared/gapi-task/scenes.json ]; then
    table gapi-task ../shared/gapi-task/scenes.json
fi
