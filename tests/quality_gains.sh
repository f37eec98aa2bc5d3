#!/bin/sh
# What mipmaps and 4 samples gain against the ground truth (sgapi-render --ground-truth 8), for
# sgapi and for lavapipe at the same settings, read from sgapi-bench --quality (its PSNRs do not
# depend on the frames measured, so --quick gives the same figures as a long run):
#   - the long checkered floor: "mipmap": "linear" gains >= 3 dB over no mipmaps;
#   - the translucent teapot: linear mipmaps gain, though less than 3 dB (about 0.9 dB, as
#     lavapipe's: its error is mostly the brick wall and edges, which mipmaps do not change);
#   - msaa_flat_edges: 4 samples gain >= 6 dB;
#   - msaa_teapot: 4 samples gain, though less than 6 dB (about 0.3 dB, as lavapipe's: it is
#     textured, and a 4-sample pixel still samples its textures once);
#   - every gain of sgapi is at least lavapipe's own minus 0.5 dB.
#   quality_gains.sh BENCH_BINARY SOURCE_DIR WORK_DIR
set -eu
bench=$1
src=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
"$bench" "$src/scenes/mipmaps.json" "$src/scenes/msaa.json" --quality --quick --threads 2 \
    --scene mip_floor_none --scene mip_teapot_none --scene msaa_flat_edges --scene msaa_teapot \
    --csv "$work/quality.csv" --plot "$work/quality.png" >"$work/quality.md"
# scene,renderer,samples,mipmap,ms,psnr_db,pct_over_8,gain_db,frontier
awk -F, '
function gain(scene, renderer, samples, mipmap) {
    key = scene "," renderer "," samples "," mipmap
    if (!(key in g)) { printf "missing row %s\n", key; bad = 1; return 0 }
    return g[key]
}
# One check: sgapi gains at least `least` dB and no less than lavapipe minus 0.5 dB.
function check(scene, samples, mipmap, least,    s, l) {
    s = gain(scene, "sgapi", samples, mipmap)
    l = gain(scene, "lavapipe", samples, mipmap)
    ok = s >= least && s >= l - 0.5
    printf "%-16s %dx %-7s gain: sgapi %+.2f dB, lavapipe %+.2f dB (needs >= %.1f and >= lavapipe - 0.5) %s\n", \
        scene, samples, mipmap, s, l, least, ok ? "ok" : "FAIL"
    if (!ok) bad = 1
}
NR > 1 { g[$1 "," $2 "," $3 "," $4] = $8 }
END {
    check("mip_floor_none", 1, "linear", 3.0)
    check("mip_teapot_none", 1, "linear", 0.5)
    check("msaa_flat_edges", 4, "none", 6.0)
    check("msaa_teapot", 4, "none", 0.1)
    exit bad
}' "$work/quality.csv"
