#!/bin/sh
# sgapi-render and a scene file with a misspelt key: without --strict it renders and warns (naming
# the file and line, the key's path and the key meant); with --strict it exits 1 and writes nothing.
#   strict_keys.sh RENDER_BINARY SOURCE_DIR WORK_DIR
set -eu
render=$1
src=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
sed 's/"lighting": "phong"/"lightning": "phong"/' "$src/scenes/lighting.json" >"$work/typo.json"
cp -r "$src/scenes/assets" "$work/assets"
line=$(grep -n '"lightning"' "$work/typo.json" | head -n 1 | cut -d: -f1)
[ -n "$line" ]

"$render" "$work/typo.json" --scene lit_point_cubes -o "$work/loose" >/dev/null 2>"$work/loose.err"
grep -q "warning: $work/typo.json:$line: unknown key 'scenes\[[0-9]*\]\.draws\[[0-9]*\]\.lightning' (did you mean 'lighting'?)" "$work/loose.err"
[ -f "$work/loose/lit_point_cubes.png" ]

status=0
"$render" "$work/typo.json" --scene lit_point_cubes -o "$work/strict" --strict >/dev/null \
    2>"$work/strict.err" || status=$?
[ "$status" -eq 1 ] || { echo "--strict exited $status, not 1"; exit 1; }
grep -q "error: $work/typo.json:$line: unknown key" "$work/strict.err"
[ ! -e "$work/strict" ] || { echo "--strict rendered something"; exit 1; }
echo "warning without --strict, exit 1 and nothing rendered with it"
