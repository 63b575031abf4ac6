#!/usr/bin/env bash
# Crash recovery: start a build of $TARGETS in a fresh copy, SIGKILL snakemake and its job
# (the whole process group) while a rule is running, and check that
#   1. no output of the cut rule exists under its final name (writes are atomic; leftovers are
#      hidden .<stem>.<uuid>.<ext> temporaries, not plausible results),
#   2. rerunning snakemake (after `snakemake --unlock`: a killed run cannot release its lock;
#      with rerun-incomplete, as the default profile) completes,
#   3. outputs finished before the kill are not rebuilt (same mtime),
#   4. every CSV/PNG is byte-identical to a clean, uninterrupted build.
set -euo pipefail
source "$(dirname "$0")/_temp_copy.sh"
WORK=$(mktemp -d -t brdfs-crash-XXXXXX)
trap 'rm -rf "$WORK"' EXIT
temp_copy "$WORK/clean"
temp_copy "$WORK/crash"
(cd "$WORK/clean" && PYTHONPATH="$WORK/clean/src" nice "$SNAKEMAKE" --cores 1 --rerun-incomplete $TARGETS > build.log 2>&1) \
    || { tail -30 "$WORK/clean/build.log"; exit 1; }

cd "$WORK/crash"
export PYTHONPATH="$WORK/crash/src"
setsid nice "$SNAKEMAKE" --cores 1 --rerun-incomplete $TARGETS > first.log 2>&1 &
PGID=$!
# Wait until one artifact is done and the next one has started (its log exists, its PNG does not).
victim=""
for _ in $(seq 1 600); do
    sleep 0.1
    done_pngs=$( (find results -name '*.png' -not -name '.*' 2>/dev/null || true) | wc -l)
    for log in $(find results/logs/tables results/logs/figures -name "*.log" 2>/dev/null || true); do
        kind=$(basename "$(dirname "$log")"); name=$(basename "$log" .log)
        if [ "$done_pngs" -ge 1 ] && [ ! -e "results/$kind/$name.png" ]; then victim="results/$kind/$name"; break; fi
    done
    [ -n "$victim" ] && break
done
[ -n "$victim" ] || { echo "check-crash: no rule was caught running"; cat first.log; exit 1; }
sleep 0.5
kill -KILL -- "-$PGID" 2>/dev/null || true
wait "$PGID" 2>/dev/null || true
echo "check-crash: SIGKILL while building $victim"

# 1. Nothing plausible left by the cut rule.
for ext in png csv; do
    if [ -e "$victim.$ext" ]; then echo "check-crash: FAILED, $victim.$ext exists after the kill"; exit 1; fi
done
leftovers=$( (find results -name '.*' -type f || true) | wc -l)
finished=$( (find results/tables results/figures -type f \( -name '*.csv' -o -name '*.png' \) -not -name '.*' 2>/dev/null || true) | LC_ALL=C sort)
stamps=$(for f in $finished; do stat -c '%Y.%y %n' "$f"; done)

# 2. The rerun completes (after removing the lock the killed run could not release).
"$SNAKEMAKE" --unlock > unlock.log 2>&1
"$SNAKEMAKE" --cores 1 --rerun-incomplete $TARGETS > second.log 2>&1 || { echo "check-crash: FAILED, rerun failed"; tail -30 second.log; exit 1; }
# 3. What was finished is not rebuilt.
for f in $finished; do
    grep -qxF "$(stat -c '%Y.%y %n' "$f")" <<< "$stamps" || { echo "check-crash: FAILED, $f was rebuilt"; exit 1; }
done
rebuilt=$(grep -c "^rule artifact:\|^localrule artifact:" second.log || true)
# 4. Same bytes as the clean build.
if ! diff -u <(fingerprint "$WORK/clean") <(fingerprint "$WORK/crash"); then
    echo "check-crash: FAILED, files differ from the clean build"; exit 1
fi
echo "check-crash: rerun completed; $(echo "$finished" | grep -c . || true) files finished before the kill kept," \
     "$rebuilt artifact jobs rerun, $leftovers hidden temporaries left by the kill," \
     "$(fingerprint "$WORK/clean" | wc -l) CSV/PNG files identical to a clean build"
