#!/usr/bin/env bash
# Wall time of forced rebuilds (issue 40's budgets: 60 s without the renders and the reading searches,
# 30 s for the searches, 60 s for the default render preset; 2 idle cores), through the pre-loaded
# parent that `make all` starts (brdfs.pipeline.zygote). Run after a complete `make all`:
#
#     benchmarks/time_rebuild.sh [RUNS] [KIND ...]
#
# KIND: nonrender (every non-render artifact but the searches), search (the reading searches), render
# (rule render_artifact), norender (nonrender and search in one run), all (--forceall). Default: all
# five. Prints one line per run: kind, run, wall seconds, jobs, exit status, the 1-minute load before.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-3}
shift || true
KINDS=${*:-nonrender search render norender all}
export PYTHONPATH=$PWD/src
SNAKEMAKE=(.venv/bin/snakemake --profile workflow/profiles/default)
LOGS=$(mktemp -d -t brdfs-rebuild-XXXXXX)

renders=" $(ls -d results/renders/*/ | xargs -n1 basename | tr '\n' ' ') "
nonrender=() searches=()
for f in results/tables/*.csv results/figures/*.csv results/checks/*.csv; do
    name=$(basename "$f" .csv)
    [[ $renders == *" $name "* ]] && continue
    case $name in
        extra_readings_*|extra_metal_a0_readings) searches+=("$f") ;;
        *) nonrender+=("$f") ;;
    esac
done

SOCKET=$PWD/.snakemake/zygote.sock
.venv/bin/python -m brdfs.pipeline.zygote "$SOCKET" &
PARENT=$!
trap 'kill $PARENT 2>/dev/null; rm -rf "$LOGS"' EXIT
export BRDFS_ZYGOTE=$SOCKET
for _ in $(seq 1 100); do [ -S "$SOCKET" ] && break; sleep 0.1; done

for run in $(seq 1 "$RUNS"); do
    for kind in $KINDS; do
        case $kind in
            nonrender) args=(--forcerun "${nonrender[@]}") ;;
            search) args=(--forcerun "${searches[@]}") ;;
            render) args=(--forcerun render_artifact) ;;
            norender) args=(--forcerun "${nonrender[@]}" "${searches[@]}") ;;
            all) args=(--forceall) ;;
            *) echo "time_rebuild.sh: unknown kind '$kind' (nonrender, search, render, norender, all)" >&2; exit 2 ;;
        esac
        load=$(cut -d' ' -f1 /proc/loadavg)
        start=$(date +%s.%N)
        status=0
        "${SNAKEMAKE[@]}" "${args[@]}" > "$LOGS/$kind.$run.log" 2>&1 || status=$?
        wall=$(echo "$(date +%s.%N) - $start" | bc)
        jobs=$(grep -c "^rule \|^localrule " "$LOGS/$kind.$run.log" || true)
        printf '%-9s run %d  wall %6.1f s  jobs %3d  status %d  load before %s\n' "$kind" "$run" "$wall" "$jobs" "$status" "$load"
    done
done
