#!/bin/sh
# bench/pool.sh LABEL JOBFILE - run the shell commands of JOBFILE (one per line, each a complete
# command with its own output redirections) on PFB_THREADS processes at once (default: every
# online core), longest first if the caller put them first. The bench's untimed steps use it
# (callgrind counts, the stability sweep's builds and shards, the GPU counts, the charts): the
# commands are independent and deterministic, so their outputs do not depend on how many run at
# once (PFB_THREADS=1 runs them one after the other, in file order).
#
# Progress on stderr once the step has run PFB_PROGRESS_AFTER seconds (default 2): "LABEL: 41%
# (9/22 jobs), 12 s elapsed, ~17 s left", updated in place on a terminal (every second) and as
# a plain line every 10 s otherwise (logs, CI); the estimate is the elapsed time scaled by the
# jobs left. A last line gives the step's wall time.
#
# Exit status: 0 when every command exited 0, else 1 (each failed command is named on stderr).
set -u
label=$1
jobfile=$2
total=$(grep -c . "$jobfile" || true)
[ "$total" -gt 0 ] || exit 0
n=${PFB_THREADS:-}
case $n in ''|*[!0-9]*|0) n=$(getconf _NPROCESSORS_ONLN 2>/dev/null || nproc 2>/dev/null || echo 1) ;; esac
[ "$n" -ge 1 ] 2>/dev/null || n=1
after=${PFB_PROGRESS_AFTER:-2}
state=$(mktemp -d "${TMPDIR:-/tmp}/pf-pool.XXXXXX") || exit 1
: > "$state/done"
: > "$state/failed"
t0=$(date +%s)

# the monitor: prints progress while the jobs run (killed below)
if [ -t 2 ]; then tty=1; every=1; else tty=0; every=10; fi
(
    last=0
    while :; do
        sleep 1
        now=$(date +%s)
        el=$((now - t0))
        [ "$el" -ge "$after" ] || continue
        [ $tty = 1 ] || [ $((now - last)) -ge $every ] || continue
        last=$now
        d=$(grep -c . "$state/done")
        if [ "$d" -gt 0 ]; then
            left=$((el * (total - d) / d))
            msg="$label: $((100 * d / total))% ($d/$total jobs), $el s elapsed, ~$left s left"
        else
            msg="$label: 0/$total jobs, $el s elapsed"
        fi
        if [ $tty = 1 ]; then printf '\r%s\033[K' "$msg" >&2; else printf '%s\n' "$msg" >&2; fi
    done
) &
mon=$!

# one command per line; the line is run by sh -c, its status recorded
grep . "$jobfile" | tr '\n' '\0' | xargs -0 -n 1 -P "$n" sh -c '
    if sh -c "$2"; then :; else echo "$2" >> "$1/failed"; fi
    echo x >> "$1/done"' pool-job "$state" >&2
kill "$mon" 2>/dev/null
wait "$mon" 2>/dev/null
el=$(($(date +%s) - t0))
[ $tty = 1 ] && [ "$el" -ge "$after" ] && printf '\r\033[K' >&2
[ "$el" -ge "$after" ] && echo "$label: done, $total jobs in $el s on $n processes" >&2
rc=0
if [ -s "$state/failed" ]; then
    rc=1
    while IFS= read -r c; do echo "$label: FAILED: $c" >&2; done < "$state/failed"
fi
rm -rf "$state"
exit $rc
