#!/bin/sh
# docs/scale-out.md's Slurm job array, submitted as written (tools/slurm/*.sbatch) to a one-node
# cluster; run inside one (tests/slurm/cluster.sh):
#   cluster.sh sh batch.sh RENDER_BINARY SOURCE_DIR WORK_DIR
# - a turntable of two scenes as an array of 4, then the assemble job (--dependency=afterok):
#   every frame and both videos byte for byte the same run's without Slurm (the docs' loop of 4
#   local shards), whose wall time it prints beside Slurm's;
# - faults: one task killed (kill -9) mid-frame, one cancelled while it runs: the assemble job
#   never runs, --assemble names the missing frames, every frame on disk is whole; submitting
#   only those two indices again renders only what is missing, and the assemble job then ends
#   the run byte-identical; a finished task requeued renders nothing twice;
# - 300 small scene files split across the array without --turntable (an index past the array's
#   size fails alone, naming its shard; a task given a missing scene file fails naming it).
set -eu
render=$1
src=$2
work=$3
scripts=$src/tools/slurm
fail() {
    echo "FAIL: $*"
    for f in "$work"/*/logs/*.out; do [ -f "$f" ] && { echo "== $f"; tail -n 5 "$f"; }; done
    exit 1
}
now() { date +%s.%N; }
since() { echo "$1" | awk -v t="$(now)" '{ printf "%.2f", t - $1 }'; }
rm -rf "$work"
mkdir -p "$work"

# The state of a job, or of an array's task (JOB TASK), as scontrol has it.
state() {
    scontrol -o show job "$1" 2>/dev/null |
        awk -v t="${2:-}" '(t == "" || index($0, " ArrayTaskId=" t " ")) {
            sub(/.*JobState=/, ""); sub(/ .*/, ""); print; exit }'
}
# Waits until none of the jobs is pending or running (60 s at most).
wait_jobs() {
    n=0
    for j in "$@"; do
        while [ -n "$(squeue -h -j "$j" -o %i 2>/dev/null)" ]; do
            n=$((n + 1))
            [ $n -lt 600 ] || fail "job $j still queued after 60 s: $(squeue -h -j "$j" -o '%i %T %r')"
            sleep 0.1
        done
    done
}
# Waits until a task's progress file has N frames done; prints the task's pid.
wait_frames() { # FILE N
    n=0
    until [ -f "$1" ] && [ "$(grep -c '"event": "done"' "$1")" -ge "$2" ]; do
        n=$((n + 1))
        [ $n -lt 600 ] || fail "$1: no $2 frames after 60 s"
        sleep 0.05
    done
    sed -n 's/.*"event": "start".*"pid": \([0-9]*\).*/\1/p' "$1" | tail -n 1
}

# Submits the docs' array and then its assembly, as docs/scale-out.md does, from folder $1 (its
# logs/ beside it); the job ids go to $jobid and $assemble.
submit() { # DIR [sbatch options of the array...]
    dir=$1
    shift
    mkdir -p "$dir/logs"
    jobid=$(cd "$dir" && sbatch --parsable "$@" "$scripts/render-turntable.sbatch" "$scene")
    assemble=$(cd "$dir" && sbatch --parsable --dependency=afterok:"$jobid" \
        "$scripts/assemble-turntable.sbatch" "$scene")
}

# ---- the turntable of two scenes: 4 tasks on Slurm against the same 4 shards run locally ----
# SLURM_TEST_FRAMES: frames of the turn (24; docs/scale-out.md times 48 and 240).
# The scene file goes to the scripts as an argument: the checkout's path may hold spaces.
scene="$src/scenes/shadows.json"
export SGAPI_RENDER="$render" TURNTABLE=${SLURM_TEST_FRAMES:-24} \
    OPTIONS="--up 0 --scene shadow_teapots --scene shadow_point --png-level 1 --video-width 256"
# shellcheck disable=SC2086
local_run() { # OUT: the docs' loop without a scheduler, one thread a shard
    for i in 0 1 2 3; do
        "$render" "$scene" -o "$1" --turntable $TURNTABLE $OPTIONS --threads 1 --quiet \
            --shard $i/4 >"$1.$i.out" &
    done
    wait
    "$render" "$scene" -o "$1" --turntable $TURNTABLE $OPTIONS --video gif,mp4 --assemble \
        >"$1.assemble.out"
    for i in 0 1 2 3; do
        tail -n 1 "$1.$i.out" | grep -q '^done: ' || fail "local shard $i: $(cat "$1.$i.out")"
    done
}
mkdir -p "$work/local"
t0=$(now)
local_run "$work/local/tt"
local_s=$(since "$t0")

t0=$(now)
OUT=$work/slurm/tt submit "$work/slurm" --array=0-3 --cpus-per-task=1
wait_jobs "$jobid" "$assemble"
slurm_s=$(since "$t0")
for i in 0 1 2 3; do
    [ "$(state "$jobid" $i)" = COMPLETED ] || fail "task $i: $(state "$jobid" $i)"
done
[ "$(state "$assemble")" = COMPLETED ] || fail "assemble job: $(state "$assemble")"
diff -r "$work/local/tt" "$work/slurm/tt" || fail "the Slurm run's files differ from the local run's"
frames=$(find "$work/slurm/tt" -name '*.png' | wc -l)
[ "$frames" -eq $((2 * TURNTABLE)) ] || fail "$frames frames, not $((2 * TURNTABLE))"
for v in shadow_teapots.gif shadow_teapots.mp4 shadow_point.gif shadow_point.mp4; do
    [ -s "$work/slurm/tt/$v" ] || fail "no $v"
done
echo "turntable, 2 scenes x $TURNTABLE frames in 4 shards, frames and videos byte-identical:"
echo "  local (4 shards at once, then --assemble): $local_s s"
echo "  Slurm (array of 4, then the assemble job): $slurm_s s"
# Each task's stdout: a line per frame, its summary last.
for i in 0 1 2 3; do
    log="$work/slurm/logs/turntable-${jobid}_$i.out"
    n=$((TURNTABLE / 2))
    [ "$(grep -c '^frame shadow_[a-z]*/[0-9]*\.png [0-9.]* ms$' "$log")" -eq $n ] ||
        fail "$log: not a line per frame"
    tail -n 1 "$log" | grep -q "^done: $n of $n frames on disk ($n rendered, 0 already there)" ||
        fail "$log: $(tail -n 1 "$log")"
done

# ---- faults: a task killed mid-frame, a task cancelled while it runs ----
# Slower frames (PNG level 9), so that the tasks are caught while they run.
export TURNTABLE=12 OPTIONS="--up 0 --scene shadow_teapots --scene shadow_point --png-level 9"
# shellcheck disable=SC2086
"$render" "$scene" -o "$work/ref" --turntable $TURNTABLE $OPTIONS --quiet >/dev/null
OUT=$work/fault/tt submit "$work/fault" --array=0-3 --cpus-per-task=1
pid=$(wait_frames "$work/fault/logs/turntable-1.jsonl" 2)
kill -KILL "$pid"
wait_frames "$work/fault/logs/turntable-2.jsonl" 2 >/dev/null
scancel "${jobid}_2"
wait_jobs "$jobid" "$assemble"
for i in 0 3; do [ "$(state "$jobid" $i)" = COMPLETED ] || fail "task $i: $(state "$jobid" $i)"; done
[ "$(state "$jobid" 1)" = FAILED ] || fail "the killed task: $(state "$jobid" 1)"
[ "$(state "$jobid" 2)" = CANCELLED ] || fail "the cancelled task: $(state "$jobid" 2)"
[ "$(state "$assemble")" = CANCELLED ] || fail "the assemble job ran: $(state "$assemble")"
ls "$work/fault/logs" | grep -q '^assemble-' && fail "the assemble job wrote a log"
# Every frame on disk is whole: each is the reference's, byte for byte.
missing=0
for f in $(cd "$work/ref" && find . -name '*.png' | sort); do
    if [ -f "$work/fault/tt/$f" ]; then
        cmp -s "$work/ref/$f" "$work/fault/tt/$f" || fail "$f on disk is not whole"
    else
        missing=$((missing + 1))
    fi
done
[ $missing -gt 0 ] || fail "the faults left no frame missing"
set +e
# shellcheck disable=SC2086
"$render" "$scene" -o "$work/fault/tt" --turntable $TURNTABLE $OPTIONS --video gif --assemble \
    >/dev/null 2>"$work/fault/assemble.err"
rc=$?
set -e
[ $rc -eq 1 ] || fail "--assemble with frames missing: exit $rc"
grep -q "of the $TURNTABLE frames of 'shadow_[a-z]*' missing or not whole" \
    "$work/fault/assemble.err" || fail "--assemble: $(cat "$work/fault/assemble.err")"
[ "$(grep -c ' is missing$' "$work/fault/assemble.err")" -eq $missing ] ||
    fail "--assemble does not name the $missing missing frames: $(cat "$work/fault/assemble.err")"
echo "faults: task 1 killed, task 2 cancelled; $missing frames missing, named by --assemble," \
    "the assemble job cancelled, every frame on disk whole"
# Only the two indices again (the array's size as SHARDS), then the assembly.
SHARDS=4 OUT=$work/fault/tt submit "$work/fault" --array=1,2 --cpus-per-task=1
wait_jobs "$jobid" "$assemble"
[ "$(state "$assemble")" = COMPLETED ] || fail "assemble after the re-run: $(state "$assemble")"
rendered=0
for i in 1 2; do
    line=$(grep '"event": "end"' "$work/fault/logs/turntable-$i.jsonl" | tail -n 1)
    echo "  task $i again: $line"
    echo "$line" | grep -q '"status": 0, "items": 6, ' || fail "task $i again: $line"
    r=$(echo "$line" | sed 's/.*"rendered": \([0-9]*\).*/\1/')
    rendered=$((rendered + r))
done
[ $rendered -eq $missing ] || fail "the re-run rendered $rendered frames, $missing were missing"
find "$work/fault/tt" -name '*.part' | grep -q . && fail "files left half-written"
# shellcheck disable=SC2086
"$render" "$scene" -o "$work/ref" --turntable $TURNTABLE $OPTIONS --video gif,mp4 --assemble \
    >/dev/null
diff -r "$work/ref" "$work/fault/tt" || fail "the run after the faults differs"
echo "faults: the two indices submitted again rendered only the $missing missing frames;" \
    "frames and videos byte-identical"
# A finished task requeued renders nothing twice (its progress file: the killed run, which has no
# end, the run again, and now the requeued one).
scontrol requeue "${jobid}_1"
n=0
until [ "$(grep -c '"event": "end"' "$work/fault/logs/turntable-1.jsonl")" -ge 2 ]; do
    n=$((n + 1))
    [ $n -lt 1200 ] || fail "the requeued task did not run in 60 s: $(state "$jobid" 1)"
    sleep 0.05
done
line=$(grep '"event": "end"' "$work/fault/logs/turntable-1.jsonl" | tail -n 1)
echo "$line" | grep -q '"status": 0, "items": 6, "rendered": 0, "skipped": 6' ||
    fail "the requeued task: $line"
echo "requeued task: $line"
diff -r "$work/ref" "$work/fault/tt" || fail "the requeued task changed the files"

# ---- a batch of 300 scene files without --turntable ----
mkdir -p "$work/scenes"
sh "$src/tests/tiny_scenes.sh" "$work/tiny.json" "$src"
python3 - "$work/tiny.json" "$work/scenes" <<'EOF'
import copy, json, math, sys
base = json.load(open(sys.argv[1]))
for i in range(300):
    scene = copy.deepcopy(base["scenes"][i % 2])  # lit_shadow, textured
    scene["name"] = "s%03d" % i
    a = math.radians(i * 7)  # turn the last draw about y: every image its own
    wv = scene["draws"][-1]["worldView"]
    c, s = math.cos(a), math.sin(a)
    for r in range(3):
        x, z = wv[4 * r], wv[4 * r + 2]
        wv[4 * r], wv[4 * r + 2] = c * x + s * z, -s * x + c * z
    out = {k: v for k, v in base.items() if k != "scenes"}
    out["scenes"] = [scene]
    json.dump(out, open("%s/s%03d.json" % (sys.argv[2], i), "w"))
EOF
"$render" "$work"/scenes/*.json -o "$work/local/batch" --quiet >/dev/null
mkdir -p "$work/batch/logs"
# 5 tasks for 4 shards: task 4 asks for shard 4/4 and fails alone.
jobid=$(cd "$work/batch" && TURNTABLE= OPTIONS= OUT="$work/batch/out" SHARDS=4 \
    sbatch --parsable --array=0-4 --cpus-per-task=1 "$scripts/render-turntable.sbatch" \
    "$work"/scenes/*.json)
wait_jobs "$jobid"
for i in 0 1 2 3; do
    [ "$(state "$jobid" $i)" = COMPLETED ] || fail "batch task $i: $(state "$jobid" $i)"
    tail -n 1 "$work/batch/logs/turntable-${jobid}_$i.out" |
        grep -q '^done: 75 of 75 images on disk (75 rendered, 0 already there)' ||
        fail "batch task $i: $(tail -n 1 "$work/batch/logs/turntable-${jobid}_$i.out")"
done
[ "$(state "$jobid" 4)" = FAILED ] || fail "batch task 4 (shard 4/4): $(state "$jobid" 4)"
grep -q "not '4/4'" "$work/batch/logs/turntable-${jobid}_4.out" ||
    fail "task 4 does not name its shard: $(cat "$work/batch/logs/turntable-${jobid}_4.out")"
diff -r "$work/local/batch" "$work/batch/out" || fail "the batch's images differ from the local run's"
echo "batch: 300 scene files in 4 tasks, images byte-identical; task 4 of 5 failed alone:" \
    "$(grep "4/4" "$work/batch/logs/turntable-${jobid}_4.out")"
# A task given a scene file that is not there fails, naming it, and writes nothing.
jobid=$(cd "$work/batch" && TURNTABLE= OPTIONS= OUT="$work/batch/out2" SHARDS=4 \
    sbatch --parsable --array=3 --cpus-per-task=1 "$scripts/render-turntable.sbatch" \
    "$work"/scenes/s00*.json "$work/scenes/gone.json")
wait_jobs "$jobid"
[ "$(state "$jobid" 3)" = FAILED ] || fail "the task with a missing file: $(state "$jobid" 3)"
grep -q "gone.json" "$work/batch/logs/turntable-${jobid}_3.out" ||
    fail "the missing file is not named: $(cat "$work/batch/logs/turntable-${jobid}_3.out")"
[ -e "$work/batch/out2" ] && fail "the task with a missing file wrote $work/batch/out2"
echo "batch: a missing scene file fails its task: $(grep gone.json "$work/batch/logs/turntable-${jobid}_3.out")"
rm -rf "$work"
echo "slurm batch: all checks passed"
