#!/usr/bin/env bash
# A local stand-in for a batch scheduler's submit command (sbatch, qsub), for the generic
# cluster executor (workflow/profiles/local-cluster, `make check-cluster`):
#     submit.sh --cpus N --mem-mb MB --runtime-min MIN JOBSCRIPT
# records the request, runs JOBSCRIPT in the background, and prints a job id. The job's
# output and exit status land in $CLUSTER_JOBS_DIR (default .cluster-jobs/), where
# status.sh reads them. A real cluster replaces this script by its own submit command.
set -euo pipefail
dir=${CLUSTER_JOBS_DIR:-.cluster-jobs}
mkdir -p "$dir"
jobscript=${!#}
id="local-$(date +%s%N)-$$"
echo "$*" > "$dir/$id.request"
nohup bash -c 'bash "$1" > "$2.out" 2>&1; echo $? > "$2.exit.tmp"; mv "$2.exit.tmp" "$2.exit"' \
    _ "$jobscript" "$dir/$id" > /dev/null 2>&1 < /dev/null &
echo "$id"
