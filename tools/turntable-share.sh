#!/bin/sh
# Prints the share of writing frames in a turntable's wall time, per way of writing them, as a
# markdown table: a 240-frame turntable of 06_teapot (scenes/default.json, 1024 x 1024) rendered
# with --no-write (R) and then written in each configuration (W), into an empty folder of DIR
# each time; the share is 1 - R / W of the same round. ROUNDS rounds (default 5), each
# configuration's seconds and share the median over them. DIR defaults to /dev/shm/sgapi-share
# (a memory file system: the CPU's cost, not a disk's).
#   tools/turntable-share.sh [BUILD_DIR] [DIR]
set -eu
build=${1:-build}
dir=${2:-/dev/shm/sgapi-share}
rounds=${ROUNDS:-5}
render="$build/apps/sgapi-render"
[ -x "$render" ] || { echo "no $render: build first" >&2; exit 2; }
scene="$(dirname "$0")/../scenes/default.json"
times=$(mktemp)
trap 'rm -f "$times"; rm -rf "$dir"' EXIT
# Configurations, one per line: sgapi-render options (none: the default).
configs='--no-write
-
--writers 1
--writers 0
--png-level 1
--png-level 1 --writers 0
--png-level 6'
seconds() { # the run's own figure: "... (240 frames in S s)"
    sed -n 's/.*frames in \([0-9.]*\) s).*/\1/p'
}
i=0
while [ "$i" -lt "$rounds" ]; do
    echo "$configs" | while IFS= read -r cfg; do
        rm -rf "$dir"
        [ "$cfg" = - ] && opts= || opts=$cfg
        # shellcheck disable=SC2086
        s=$("$render" "$scene" --scene 06_teapot -o "$dir" --turntable 240 --quiet $opts | seconds)
        mb=$(du -sm "$dir" 2>/dev/null | cut -f1)
        echo "$i|$cfg|$s|${mb:-0}" >>"$times"
    done
    i=$((i + 1))
done
echo "| sgapi-render options | frames/s | s for 240 | writing's share | MB for 240 |"
echo "| --- | ---: | ---: | ---: | ---: |"
awk -F'|' '
    $2 == "--no-write" { r[$1] = $3 }
    { s[$2, ++n[$2]] = $3; round[$2, n[$2]] = $1; mb[$2] = $4; if (!($2 in seen)) { seen[$2] = 1; order[++k] = $2 } }
    function median(a, m,    i, j, t) { # sorts a[1..m] in place
        for (i = 2; i <= m; i++) for (j = i; j > 1 && a[j - 1] > a[j]; j--) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
        return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
    }
    END {
        for (c = 1; c <= k; c++) {
            cfg = order[c]; m = n[cfg]
            for (j = 1; j <= m; j++) { t[j] = s[cfg, j]; sh[j] = 1 - r[round[cfg, j]] / s[cfg, j] }
            sec = median(t, m)
            share = cfg == "--no-write" ? "–" : sprintf("%.0f %%", 100 * median(sh, m))
            name = cfg == "-" ? "none (level 0, two writers)" : "`" cfg "`"
            printf "| %s | %.0f | %.3f | %s | %s |\n", name, 240 / sec, sec, share, cfg == "--no-write" ? "–" : mb[cfg]
        }
    }' "$times"
