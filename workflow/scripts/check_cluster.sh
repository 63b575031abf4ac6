#!/usr/bin/env bash
# The cluster path for real, on this machine: build $TARGETS in a fresh copy with the profile
# workflow/profiles/local-cluster, where the generic cluster executor submits every job through
# workflow/cluster/submit.sh and polls workflow/cluster/status.sh. Checks that every job was
# submitted with its declared threads/memory/runtime, finished with exit status 0, and that
# every target exists.
set -euo pipefail
source "$(dirname "$0")/_temp_copy.sh"
WORK=$(mktemp -d -t brdfs-cluster-XXXXXX)
trap 'rm -rf "$WORK"' EXIT
temp_copy "$WORK/run"
cd "$WORK/run"
export PYTHONPATH="$WORK/run/src"
nice "$SNAKEMAKE" --profile workflow/profiles/local-cluster $TARGETS > build.log 2>&1 \
    || { tail -40 build.log; for f in .cluster-jobs/*.out; do echo "== $f"; tail -20 "$f"; done; exit 1; }
submitted=$(grep -c "with external jobid 'local-" build.log || true)
requests=$(ls .cluster-jobs/*.request | wc -l)
ok=$(grep -lx 0 .cluster-jobs/*.exit | wc -l)
[ "$submitted" -ge 1 ] && [ "$submitted" = "$requests" ] && [ "$ok" = "$requests" ] \
    || { echo "check-cluster: FAILED, $submitted submitted, $requests requests, $ok succeeded"; exit 1; }
grep -q -- "--cpus 1 --mem-mb [0-9]* --runtime-min [0-9]*" .cluster-jobs/*.request \
    || { echo "check-cluster: FAILED, resources not passed to submit.sh"; exit 1; }
for t in $TARGETS; do [ -s "$t" ] || { echo "check-cluster: FAILED, $t missing"; exit 1; }; done
echo "check-cluster: $submitted jobs submitted through workflow/cluster/submit.sh" \
     "(e.g. '$(head -c 60 "$(ls .cluster-jobs/*.request | head -1)")'), all exited 0; $(echo $TARGETS | wc -w) targets built"
