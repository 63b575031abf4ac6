#!/usr/bin/env bash
# Crash recovery, through the README's rebuild command: in a fresh copy, start `make all` (the whole
# build, renders included; CRASH_TARGETS="..." for a part of it), SIGKILL make, flock, snakemake and
# its jobs (the whole process group) while a job is running, run the same `make all` again (nothing
# by hand: no `snakemake --unlock`), and check
#   0. a second `make all` while the first runs fails at once, with one line, and writes nothing,
#   1. the kill left Snakemake's lock behind (what the rerun must get past), and every output of
#      the cut jobs that exists under its final name is complete (writes are atomic; leftovers are
#      hidden .<stem>.<uuid>.<ext> temporaries, not plausible results),
#   2. the rerun completes (the Makefile clears the stale lock under its flock; rerun-incomplete),
#   3. outputs finished before the kill are not rebuilt (same mtime), the cut ones are,
#   4. every CSV, PNG and EXR under results/ (logs and timings apart) is byte-identical to a clean,
#      uninterrupted `make all` of the same targets.
# Minutes (two whole builds); not part of `make test`.
# The copies share this tree's .venv (a symlink; `-o .venv/.installed`: never reinstalled).
set -euo pipefail
source "$(dirname "$0")/_temp_copy.sh"
TARGETS=${CRASH_TARGETS-}
WORK=$(mktemp -d -t brdfs-crash-XXXXXX)
trap 'rm -rf "$WORK"' EXIT
unset MAKEFLAGS MAKELEVEL MFLAGS

copy() {
    temp_copy "$1"
    cp -a "$ROOT/Makefile" "$ROOT/requirements.lock" "$1"/
    ln -s "$ROOT/.venv" "$1/.venv"
}
# The README's rebuild command, for $TARGETS.
MAKE_ALL=(make --no-print-directory -o .venv/.installed all "TARGETS=$TARGETS")
# Outputs of the jobs running now: Snakemake marks them in .snakemake/incomplete/ (file names are
# the url-safe base64 of the path, cut into directories of at most 255 characters).
running_outputs() {
    [ -d .snakemake/incomplete ] || return 0
    (cd .snakemake/incomplete && find . -type f ! -name migration_underway) | sed 's|^\./||; s|/||g' \
        | while read -r id; do printf '%s' "$id" | tr '_-' '/+' | base64 -d 2>/dev/null && echo; done | LC_ALL=C sort
}
outputs() {
    (find results/tables results/figures results/checks -type f \( -name '*.csv' -o -name '*.png' \) \
        -not -name '.*' 2>/dev/null || true) | LC_ALL=C sort
}

copy "$WORK/clean"
copy "$WORK/crash"
(cd "$WORK/clean" && nice "${MAKE_ALL[@]}" > build.log 2>&1) \
    || { tail -30 "$WORK/clean/build.log"; exit 1; }

cd "$WORK/crash"
setsid nice "${MAKE_ALL[@]}" > first.log 2>&1 &
PGID=$!
# Wait until a job has finished and one is running whose outputs do not all exist yet.
cut=""
for _ in $(seq 1 6000); do  # at most 10 minutes: on a busy machine the first job (a render) takes minutes
    sleep 0.1
    cut=$(running_outputs)
    if [ -n "$(LC_ALL=C comm -23 <(outputs) <(echo "$cut"))" ]; then
        for f in $cut; do [ -e "$f" ] || break 2; done
    fi
    cut=""
    kill -0 "$PGID" 2>/dev/null || break
done
[ -n "$cut" ] || { echo "check-crash: no job was caught running"; cat first.log; exit 1; }

# 0. A second build while this one runs: refused at once, with one line, writing nothing.
before=$(outputs)
if "${MAKE_ALL[@]}" > concurrent.log 2>&1; then echo "check-crash: FAILED, a second make all ran beside the first"; exit 1; fi
grep -q "another build is running (lock held: $WORK/crash/.snakemake/make.lock)" concurrent.log \
    || { echo "check-crash: FAILED, the second make all did not say why it stopped:"; cat concurrent.log; exit 1; }
grep -q "snakemake --profile" concurrent.log && { echo "check-crash: FAILED, the second make all started snakemake"; exit 1; }

kill -KILL -- "-$PGID" 2>/dev/null || true
wait "$PGID" 2>/dev/null || true
# As a user would: rerun once the killed processes are gone (until then they hold the flock, and
# `make all` would say, rightly, that another build is running).
while kill -0 -- "-$PGID" 2>/dev/null; do sleep 0.1; done
cut=$(running_outputs)
[ -n "$cut" ] || { echo "check-crash: the build ended before the kill; rerun"; exit 1; }
echo "check-crash: a second make all during the build: $(grep -o 'another build is running.*' concurrent.log)"
echo "check-crash: SIGKILL while building $(echo $cut)"

# 1. The lock is left behind; whatever of the cut jobs exists under its final name is complete.
[ -n "$(ls -A .snakemake/locks 2>/dev/null)" ] || { echo "check-crash: FAILED, the kill left no Snakemake lock"; exit 1; }
for f in $cut; do
    if [ -e "$f" ] && ! cmp -s "$f" "$WORK/clean/$f"; then echo "check-crash: FAILED, $f is a partial file"; exit 1; fi
done
leftovers=$( (find results -name '.*' -type f || true) | wc -l)
finished=$(LC_ALL=C comm -23 <(outputs) <(echo "$cut"))
stamps=$(for f in $finished; do stat -c '%Y.%y %n' "$f"; done)

# 2. The same command again completes, with no manual step.
"${MAKE_ALL[@]}" > second.log 2>&1 || { echo "check-crash: FAILED, the rerun failed"; tail -30 second.log; exit 1; }
grep -q "clearing the Snakemake lock of a run that was killed" second.log \
    || { echo "check-crash: FAILED, the rerun did not clear the stale lock"; cat second.log; exit 1; }
# 3. What was finished is not rebuilt; what was cut is.
for f in $finished; do
    grep -qxF "$(stat -c '%Y.%y %n' "$f")" <<< "$stamps" || { echo "check-crash: FAILED, $f was rebuilt"; exit 1; }
done
for f in $cut; do [ -e "$f" ] || { echo "check-crash: FAILED, $f is missing after the rerun"; exit 1; }; done
rerun_jobs=$(grep -c "^rule \|^localrule " second.log || true)
# 4. Same bytes as the clean build.
if ! diff -u <(fingerprint "$WORK/clean") <(fingerprint "$WORK/crash"); then
    echo "check-crash: FAILED, files differ from the clean build"; exit 1
fi
echo "check-crash: the same make all completed (stale lock cleared under the flock);" \
     "$(echo "$finished" | grep -c . || true) files finished before the kill kept, $rerun_jobs jobs run," \
     "$leftovers hidden temporaries left by the kill," \
     "$(fingerprint "$WORK/clean" | wc -l) CSV/PNG/EXR files identical to a clean build"
