#!/bin/sh
# The quality picture of the README: the long checkered floor and the translucent teapot of
# scenes/mipmaps.json, each drawn by sgapi in every quality setting (1 and 4 samples x mipmap
# none, nearest, linear) beside its ground truth (sgapi-render --ground-truth 8), every tile a
# part of the image at its own pixels (scaling would hide the aliasing) with its PSNR against the
# ground truth (sgapi-diff) under it.
#   tools/quality-picture.sh [BUILD_DIR] [OUT.png]     (defaults: build, docs/images/quality.png)
# Needs ffmpeg; with its drawtext filter each tile is captioned, without it the tiles are joined
# bare and the captions are printed instead. The PSNRs are printed in any case.
set -eu
build=${1:-build}
out=${2:-docs/images/quality.png}
render=$build/apps/sgapi-render
diff=$build/apps/sgapi-diff
scenes=$(dirname "$0")/../scenes/mipmaps.json
[ -x "$render" ] && [ -x "$diff" ] || { echo "quality-picture: no $render or $diff (build first)" >&2; exit 1; }
command -v ffmpeg >/dev/null || { echo "quality-picture: needs ffmpeg" >&2; exit 1; }
text=0
ffmpeg -hide_banner -filters 2>/dev/null | grep -q ' drawtext ' && text=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# scene  crop (w:h:x:y, a part where the settings differ most)
set -- mip_floor_none 360:180:220:192 mip_teapot_none 360:240:190:290
settings="1:none 1:nearest 1:linear 4:none 4:nearest 4:linear"
rows=
while [ $# -gt 0 ]; do
    scene=$1 crop=$2
    shift 2
    "$render" "$scenes" --scene "$scene" --ground-truth 8 -o "$work/truth" >/dev/null
    tiles="$work/truth/$scene.png"
    captions="ground truth (8x8 samples)"
    for s in $settings; do
        samples=${s%%:*} mipmap=${s#*:}
        dir=$work/${samples}_$mipmap
        "$render" "$scenes" --scene "$scene" --samples "$samples" --mipmap "$mipmap" -o "$dir" >/dev/null
        psnr=$("$diff" "$dir/$scene.png" "$work/truth/$scene.png" | awk '$1 == "psnr_db" { print $2 }')
        echo "$scene ${samples}x $mipmap: $psnr dB against the ground truth"
        tiles="$tiles $dir/$scene.png"
        captions="$captions|${samples}x  mipmap $mipmap  $psnr dB"
    done
    # One row: each tile cropped, captioned below (when drawtext is there: captions hold no
    # colon or comma, which the filter graph would take as separators), then stacked.
    i=0 inputs= filters= labels=
    for t in $tiles; do
        caption=$(echo "$captions" | cut -d'|' -f$((i + 1)))
        inputs="$inputs -i $t"
        f="[$i:v]crop=$crop"
        [ "$text" = 1 ] && f="$f,pad=iw+6:ih+30:3:0:white,drawtext=text='$caption':x=8:y=h-23:fontsize=15:fontcolor=black"
        [ "$text" = 1 ] || { f="$f,pad=iw+6:ih:3:0:white"; echo "  tile $((i + 1)): $caption"; }
        filters="$filters$f[t$i];"
        labels="$labels[t$i]"
        i=$((i + 1))
    done
    # shellcheck disable=SC2086
    ffmpeg -hide_banner -loglevel error -y $inputs \
        -filter_complex "${filters}${labels}hstack=inputs=$i" "$work/row_$scene.png"
    rows="$rows $work/row_$scene.png"
done
set -- $rows
ffmpeg -hide_banner -loglevel error -y -i "$1" -i "$2" -filter_complex \
    "[0:v]pad=iw:ih+6:0:0:white[a];[a][1:v]vstack=inputs=2" "$out"
echo "quality-picture: wrote $out"
