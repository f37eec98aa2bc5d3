#!/bin/sh
# The regression report of `make test`: every scene file given, rendered once and compared with
# the golden images of the folders REFS (a ;-separated list, merged into one golden folder; a
# later folder's image of a name wins), against the targets of THRESHOLDS. Writes
# BUILD/report/index.html, BUILD/report/results.json and BUILD/junit.xml; fails as the run fails.
#   make_report.sh RENDER_BINARY THRESHOLDS BUILD_DIR REFS SCENE.json...
set -eu
render=$1
thresholds=$2
build=$3
refs=$4
shift 4
golden=$build/image_checks/report_golden
rm -rf "$golden" "$build/report"
mkdir -p "$golden"
IFS=';'
for dir in $refs; do
    cp "$dir"/*.png "$golden/"
done
unset IFS
exec "$render" "$@" -o "$build/image_checks/report_run" --compare "$golden" \
    --thresholds "$thresholds" --report "$build/report" --junit "$build/junit.xml"
