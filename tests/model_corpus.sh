#!/bin/sh
# Model files written by other tools (Debian's assimp-testmodels and geomview) through
# `sgapi-render MODEL -o DIR`, one run per file: each renders, or fails with exit 1 and a message
# that names the file. None may crash, hang (a time limit), or take more memory than a limit far
# below what a header's counts could claim. The files known to be unreadable (UTF-16 text, 4-D
# OFF, points only, broken on purpose) must fail; every other must render.
#   model_corpus.sh RENDER_BINARY SOURCE_DIR WORK_DIR
set -eu
render=$1
src=$2
work=$3
rm -rf "$work"
mkdir -p "$work"

assimp=/usr/share/assimp/models
geomview=/usr/share/geomview
for d in "$assimp" "$geomview"; do
    [ -d "$d" ] || { echo "FAIL: $d missing (tools/install-deps.sh installs it)"; exit 1; }
done

# Files that cannot be drawn, each for a reason the loaders name.
expected_failures="
$assimp/OBJ/box_UTF16BE.obj
$assimp/OBJ/number_formats.obj
$assimp/OBJ/point_cloud.obj
$assimp/OBJ/testpoints.obj
$assimp/OFF/invalid.off
$assimp/invalid/OutOfMemory.off
$assimp/invalid/empty.obj
$assimp/invalid/empty.off
$assimp/invalid/malformed.obj
$assimp/invalid/malformed2.obj
$geomview/geom/hypercube.off
$geomview/geom/spherical/dodecaplex.off
$geomview/geom/spherical/hypercube.off
$geomview/geom/spherical/octaplex.off
$geomview/geom/spherical/orthoplex.off
$geomview/geom/spherical/simplex.off
$geomview/geom/spherical/tetraplex.off
$geomview/geom/textured/dodec.off
$geomview/geom/textured/square.off
$geomview/geom/trapezoid.4d.off
"

# Runs a command under a time limit and 1 GB of memory: the device and its threads need a
# fraction of it; a loader that believed a header's counts would need far more. Under
# AddressSanitizer (which reserves terabytes of address space for itself) the limit is its own
# on resident memory instead.
limited() {
    if [ -n "${ASAN_OPTIONS:-}" ]; then
        ASAN_OPTIONS="$ASAN_OPTIONS:hard_rss_limit_mb=1000" timeout 120 "$@"
    else
        (ulimit -v 1000000 && exec timeout 60 "$@")
    fi
}

# ---- bad input of our own: what is missing is warned of once and left out ----
mkdir -p "$work/bad"
cat >"$work/bad/no_mtl.obj" <<'OBJ'
mtllib missing.mtl
usemtl red
v 0 0 0
v 1 0 0
v 0 1 0
f 1 2 3
OBJ
cat >"$work/bad/no_tex.mtl" <<'MTL'
newmtl a
Kd 1 0.5 0.25
map_Kd missing.png
newmtl b
map_Kd missing.png
MTL
cat >"$work/bad/no_tex.obj" <<'OBJ'
mtllib no_tex.mtl
v 0 0 0
v 1 0 0
v 0 1 0
v nan 1 1
vt 0 0
vt 1 0
vt 0 1
usemtl a
f 1/1 2/2 3/3
usemtl b
f 1/1 3/3 2/2
f 1/1 2/2 4/3
OBJ
check_warns() { # file, expected text of its one warning
    rc=0
    limited "$render" "$work/bad/$1" -o "$work/bad" --size 64x48 >/dev/null 2>"$work/bad/$1.err" ||
        rc=$?
    [ $rc -eq 0 ] || { echo "FAIL: $1 did not render: $(cat "$work/bad/$1.err")"; exit 1; }
    [ -f "$work/bad/${1%.obj}.png" ] || { echo "FAIL: $1: no image"; exit 1; }
    n=$(grep -c -F "$2" "$work/bad/$1.err" || true)
    [ "$n" -eq 1 ] || { echo "FAIL: $1: '$2' warned $n times: $(cat "$work/bad/$1.err")"; exit 1; }
}
check_warns no_mtl.obj "material library"
check_warns no_tex.obj "missing.png' not found"

files=$(find "$assimp/OBJ" "$assimp/OFF" "$assimp/invalid" "$geomview" \
    \( -name '*.obj' -o -name '*.off' \) -type f | sort)
files="$files
$src/scenes/assets/dodecahedron.off"
status=0
n=0
rendered=0
# One file a line: the checkout's path may hold blanks. The list is split once, as the loop
# starts; its body runs with the usual splitting and globbing.
newline='
'
IFS=$newline
set -f
for f in $files; do
    unset IFS
    set +f
    n=$((n + 1))
    out="$work/$n"
    mkdir -p "$out"
    rc=0
    limited "$render" "$f" -o "$out" --size 160x120 --threads 1 >"$out/stdout" 2>"$out/stderr" ||
        rc=$?
    expect_fail=no
    case "$expected_failures" in *"
$f
"*) expect_fail=yes ;;
    esac
    if [ $rc -eq 0 ]; then
        if [ $expect_fail = yes ]; then
            echo "FAIL: $f rendered, but it should fail"
            status=1
        elif [ "$(ls "$out"/*.png 2>/dev/null | wc -l)" -ne 1 ]; then
            echo "FAIL: $f: exit 0 but no image"
            status=1
        else
            rendered=$((rendered + 1))
        fi
    elif [ $rc -eq 1 ]; then
        if [ $expect_fail = no ]; then
            echo "FAIL: $f did not render: $(cat "$out/stderr")"
            status=1
        elif ! grep -q -F "$f" "$out/stderr"; then
            echo "FAIL: $f: the message does not name the file: $(cat "$out/stderr")"
            status=1
        fi
    else
        echo "FAIL: $f: exit status $rc (crash, time limit or memory limit): $(cat "$out/stderr")"
        status=1
    fi
done
echo "$n files: $rendered rendered, $((n - rendered)) refused with a message"
exit $status
