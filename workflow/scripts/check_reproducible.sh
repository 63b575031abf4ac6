#!/usr/bin/env bash
# Two clean rebuilds of $TARGETS, each in its own fresh copy of the workflow, must give
# byte-identical CSV and PNG files (sha256 of every file under results/{tables,figures,checks}).
set -euo pipefail
source "$(dirname "$0")/_temp_copy.sh"
WORK=$(mktemp -d -t brdfs-reproducible-XXXXXX)
trap 'rm -rf "$WORK"' EXIT
for run in a b; do
    temp_copy "$WORK/$run"
    (cd "$WORK/$run" && PYTHONPATH="$WORK/$run/src" nice "$SNAKEMAKE" --cores 1 $TARGETS > build.log 2>&1) \
        || { tail -30 "$WORK/$run/build.log"; exit 1; }
    fingerprint "$WORK/$run" > "$WORK/$run.sha256"
done
if ! diff -u "$WORK/a.sha256" "$WORK/b.sha256"; then
    echo "check-reproducible: FAILED, the two rebuilds differ (above)"; exit 1
fi
echo "check-reproducible: $(wc -l < "$WORK/a.sha256") CSV/PNG files byte-identical in two clean rebuilds"
