#!/usr/bin/env bash
# Status of a job submitted by submit.sh: prints running, success or failed (as the generic
# cluster executor expects from a status command).
set -euo pipefail
exit_file="${CLUSTER_JOBS_DIR:-.cluster-jobs}/$1.exit"
if [ ! -f "$exit_file" ]; then
    echo running
elif [ "$(cat "$exit_file")" = 0 ]; then
    echo success
else
    echo failed
fi
