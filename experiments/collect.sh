#!/usr/bin/env bash
# One CSV row per run set under $OUT/runs (paper_tools summary: replica means and standard errors
# of cost, collisions, events, energy conservation, temperature) plus its recorded failures: the
# compact record of every run that results/ keeps (the run directories themselves are not kept).
source "$(dirname "$0")/common.sh"
echo "$("$TOOLS" summary-header),failed_seeds"
for d in "$RUNS"/*/*/; do
    d=${d%/}
    set=${d#"$RUNS"/}
    mapfile -t dirs < <(replica_dirs "$d")
    failed=$( [ -f "$d/failures.txt" ] && wc -l <"$d/failures.txt" || echo 0)
    if [ "${#dirs[@]}" -gt 0 ]; then
        echo "$("$TOOLS" summary "$set" "${dirs[@]}"),$failed"
    fi
done
# Single extreme runs (not replica sets).
for d in "$RUNS"/extremes/*/; do
    d=${d%/}
    [ -s "$d/summary.json" ] && echo "$("$TOOLS" summary "extremes/$(basename "$d")" "$d"),0"
done
exit 0
