#!/bin/sh
# Image regression as a CI user runs it (sgapi-render --compare with --thresholds, --junit,
# --report and --update-golden), on the small scenes of tests/tiny_scenes.sh (suite "tiny") and
# the default scenes (suite "default", against their committed goldens):
# - new scenes get goldens with --update-golden (added, the default goldens untouched);
# - deliberate regressions: a golden of another size (textured), another scene's image
#   (06_teapot), a missing file (empty): exit 1, each named on stderr with its reason, the JUnit
#   file parses and names exactly those as failures, with attachments; results.json agrees;
#   the report folder holds every image it shows (the browser test opens it: report_browser.py);
# - --update-golden replaces exactly those (the others byte for byte alone), then the same run
#   exits 0; a golden that is not an image fails its scene;
# - bad input: a malformed thresholds file, a GOLDEN that is a file, an unwritable report folder,
#   a JUnit path that is a folder: exit 2 with a clear message, before anything renders.
#   regression.sh RENDER_BINARY SOURCE_DIR WORK_DIR PYTHON3
set -eu
render=$1
src=$2
work=$3
py=$4
rm -rf "$work"
mkdir -p "$work/golden"
sh "$src/tests/tiny_scenes.sh" "$work/tiny.json" "$src"
cp "$src"/golden/0*.png "$work/golden/"
fail() {
    echo "FAIL: $*"
    exit 1
}
# sgapi-render on the two scene files, with the arguments given (the paths quoted: the checkout's
# may hold blanks).
render_files() { "$render" "$work/tiny.json" "$src/scenes/default.json" "$@"; }
# Per-scene targets: a row of suite "tiny", a row for any suite with an empty and a missing
# trailing column (both keep the default).
cat >"$work/thresholds.csv" <<'EOF'
suite,scene,min_psnr_db,max_pct_over_2,max_coverage_pct
# comments and blank lines are skipped

tiny,lit_shadow,45,0.25,0
*,01_colored_triangle,,0.4
EOF

# ---- new scenes: goldens added, the others left alone ----
set +e
# shellcheck disable=SC2086
render_files -o "$work/out0" --compare "$work/golden" --update-golden >"$work/bless.out" \
    2>"$work/bless.err"
rc=$?
set -e
[ $rc -eq 0 ] || fail "--update-golden of new scenes: exit $rc: $(cat "$work/bless.err")"
for s in lit_shadow textured empty; do
    grep -q "^added  *$work/golden/$s.png " "$work/bless.out" || fail "$s not listed as added"
    cmp -s "$work/out0/$s.png" "$work/golden/$s.png" || fail "$s: golden is not the render"
done
for f in "$src"/golden/0*.png; do
    cmp -s "$f" "$work/golden/$(basename "$f")" || fail "a passing golden changed: $f"
done

# ---- regressions ----
cp "$work/golden/lit_shadow.png" "$work/golden/textured.png"        # 48x36, the scene 33x25
cp "$src/golden/07_many_teapots.png" "$work/golden/06_teapot.png"   # another scene's image
rm "$work/golden/empty.png"                                        # missing
cp -r "$work/golden" "$work/golden.before"
set +e
# shellcheck disable=SC2086
render_files -o "$work/out" --compare "$work/golden" --thresholds "$work/thresholds.csv" \
    --junit "$work/junit.xml" --report "$work/report" >"$work/run.out" 2>"$work/run.err"
rc=$?
set -e
[ $rc -eq 1 ] || fail "exit $rc with three regressions, not 1: $(cat "$work/run.err")"
[ "$(grep -c '^sgapi-render: FAIL ' "$work/run.err")" -eq 3 ] ||
    fail "not three failures on stderr: $(cat "$work/run.err")"
grep -q "FAIL tiny/textured: golden image .* is 48x36, the scene 33x25" "$work/run.err" ||
    fail "the size mismatch is not named: $(cat "$work/run.err")"
grep -q "FAIL default/06_teapot: PSNR [0-9.]* dB < 40 dB" "$work/run.err" ||
    fail "the wrong image is not named with its PSNR and threshold: $(cat "$work/run.err")"
grep -q "FAIL tiny/empty: golden image unreadable or missing" "$work/run.err" ||
    fail "the missing golden is not named: $(cat "$work/run.err")"
grep -q "^8 of 11 scenes passed, 3 failed" "$work/run.out" || fail "no summary: $(cat "$work/run.out")"
"$py" - "$work" <<'EOF' || fail "JUnit or results.json"
import json, os, sys
import xml.etree.ElementTree as ET
work = sys.argv[1]
root = ET.parse(os.path.join(work, "junit.xml")).getroot()
assert root.tag == "testsuites", root.tag
assert root.get("tests") == "11" and root.get("failures") == "3", root.attrib
cases, failed = {}, set()
for suite in root.findall("testsuite"):
    assert int(suite.get("tests")) == len(suite.findall("testcase")), suite.attrib
    assert int(suite.get("failures")) == len(suite.findall("testcase/failure")), suite.attrib
    float(suite.get("time"))
    for case in suite.findall("testcase"):
        assert case.get("classname") == suite.get("name"), case.attrib
        name = case.get("name")
        assert float(case.get("time")) >= 0, case.attrib
        cases[name] = case
        f = case.find("failure")
        if f is not None:
            assert f.get("message"), case.attrib
            failed.add(name)
assert failed == {"textured", "06_teapot", "empty"}, failed
assert {c.get("classname") for c in cases.values()} == {"tiny", "default"}
assert len(cases) == 11, sorted(cases)
assert "< 40 dB" in cases["06_teapot"].find("failure").get("message")
out = cases["06_teapot"].find("system-out").text
for kind in ("actual", "heat"):
    line = "[[ATTACHMENT|%s/report/img/06_teapot.%s.png]]" % (work, kind)
    assert line in out, out
    assert os.path.isfile(line[13:-2]), line
res = json.load(open(os.path.join(work, "report", "results.json")))
assert (res["passed"], res["failed"]) == (8, 3), res
order = [r["scene"] for r in res["results"]]
assert set(order[:3]) == failed, order
t = {r["scene"]: r["thresholds"] for r in res["results"]}
assert t["lit_shadow"] == {"min_psnr_db": 45, "max_pct_over_2": 0.25, "max_coverage_pct": 0}, t
assert t["01_colored_triangle"] == {"min_psnr_db": 40, "max_pct_over_2": 0.4,
                                    "max_coverage_pct": 0.05}, t
for r in res["results"]:
    for kind, rel in r["images"].items():
        assert rel is None or os.path.isfile(os.path.join(work, "report", rel)), rel
assert res["results"][order.index("empty")]["images"]["expected"] is None
EOF
cmp -s "$work/out/06_teapot.png" "$work/report/img/06_teapot.actual.png" || fail "report's copy"

# ---- --update-golden: only the failing scenes, then the same run passes ----
set +e
# shellcheck disable=SC2086
render_files -o "$work/out2" --compare "$work/golden" --thresholds "$work/thresholds.csv" \
    --update-golden >"$work/update.out" 2>"$work/update.err"
rc=$?
set -e
[ $rc -eq 0 ] || fail "--update-golden: exit $rc: $(cat "$work/update.err")"
grep -q "^replaced $work/golden/textured.png " "$work/update.out" || fail "textured not replaced"
grep -q "^replaced $work/golden/06_teapot.png " "$work/update.out" || fail "06_teapot not replaced"
grep -q "^added  *$work/golden/empty.png " "$work/update.out" || fail "empty not added"
[ "$(grep -c '^replaced\|^added' "$work/update.out")" -eq 3 ] || fail "more than 3 updated"
for f in "$work"/golden.before/*.png; do
    case $(basename "$f") in textured.png | 06_teapot.png) continue ;; esac
    cmp -s "$f" "$work/golden/$(basename "$f")" || fail "a passing golden changed: $f"
done
# shellcheck disable=SC2086
render_files -o "$work/out3" --compare "$work/golden" --thresholds "$work/thresholds.csv" \
    >"$work/again.out" 2>&1 || fail "the run after --update-golden: $(cat "$work/again.out")"

# ---- an unreadable golden (not a PNG) fails its scene, with the reason ----
mkdir -p "$work/corrupt"
echo "not an image" >"$work/corrupt/lit_shadow.png"
set +e
"$render" "$work/tiny.json" --scene lit_shadow -o "$work/out4" --compare "$work/corrupt" \
    >"$work/corrupt.out" 2>"$work/corrupt.err"
rc=$?
set -e
[ $rc -eq 1 ] || fail "an unreadable golden: exit $rc, not 1"
grep -q "FAIL tiny/lit_shadow: golden image unreadable or missing: .*lit_shadow.png" \
    "$work/corrupt.err" || fail "the unreadable golden is not named: $(cat "$work/corrupt.err")"

# ---- bad input: exit 2, nothing rendered ----
bad() { # what expected-message args...
    what=$1
    msg=$2
    shift 2
    rm -rf "$work/bad"
    set +e
    "$render" "$work/tiny.json" -o "$work/bad" "$@" >"$work/bad.out" 2>"$work/bad.err"
    rc=$?
    set -e
    [ $rc -eq 2 ] || fail "$what: exit $rc, not 2"
    grep -q "$msg" "$work/bad.err" || fail "$what: message '$(cat "$work/bad.err")'"
    [ -z "$(ls "$work/bad" 2>/dev/null)" ] || fail "$what: rendered before the error"
}
printf 'tiny,lit_shadow,40\ntiny,textured,forty\n' >"$work/bad.csv"
bad "malformed CSV" "bad.csv:2: min_psnr_db is 'forty', not a number" \
    --compare "$work/golden" --thresholds "$work/bad.csv"
printf 'tiny,lit_shadow,40,0.5,0.05,9\n' >"$work/bad.csv"
bad "CSV with 6 columns" "bad.csv:1: 6 fields" --compare "$work/golden" --thresholds "$work/bad.csv"
printf '# x\ntiny,textured\ntiny,textured,30\n' >"$work/bad.csv"
bad "CSV with a repeated row" "bad.csv:3: a second row" --compare "$work/golden" \
    --thresholds "$work/bad.csv"
bad "missing CSV" "no-such.csv" --compare "$work/golden" --thresholds "$work/no-such.csv"
bad "GOLDEN a file" "'$work/tiny.json' is not a folder" --compare "$work/tiny.json"
bad "GOLDEN missing" "no folder '$work/nowhere'" --compare "$work/nowhere"
bad "report under a file" "cannot create folder '$work/tiny.json'" --compare "$work/golden" \
    --report "$work/tiny.json/report"
bad "JUnit a folder" "is not a file" --compare "$work/golden" --junit "$work/golden"
bad "--report without --compare" "need --compare" --report "$work/r"
echo "regression: all checks passed"
