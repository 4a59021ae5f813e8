#!/usr/bin/env bash
# Busy-core benchmark (docs/performance.md, "Busy cores: the OpenMP wait policy").
# Runs the axisymmetric copper Taylor bar (examples/taylor_bar_mpm.yaml, full size 0.2 mm cells,
# 10,368 particles) to END_TIME at --threads 1 and 2, each alone and beside a busy process
# (`yes > /dev/null`, not pinned: the scheduler places it), and prints the wall time and the
# particle-steps/s that `ballista run` reports. Speed is measured here, never in the tests.
#
#   bench/busy_core_bench.sh [BUILD_DIR]                        # ballista's default wait policy
#   GOMP_SPINCOUNT=300000 bench/busy_core_bench.sh [BUILD_DIR]  # libgomp's default (before)
#
# Environment: END_TIME (default 20e-6 s: ~1,600 steps, ~10-15 s at 1 thread), REPEAT (runs per
# case, default 2), and any OMP_WAIT_POLICY / GOMP_SPINCOUNT, passed on unchanged (ballista
# chooses its own policy only when neither is set).
set -euo pipefail

BUILD=${1:-build}
END_TIME=${END_TIME:-20e-6}
REPEAT=${REPEAT:-2}
here=$(cd "$(dirname "$0")" && pwd)
deck="$here/../examples/taylor_bar_mpm.yaml"
exe="$BUILD/ballista"
[ -x "$exe" ] || { echo "no $exe (make build)" >&2; exit 1; }

out=$(mktemp -d)
busy_pid=""
stop_busy() {
  if [ -n "$busy_pid" ]; then
    kill "$busy_pid" 2>/dev/null || true
    wait "$busy_pid" 2>/dev/null || true
    busy_pid=""
  fi
}
trap 'stop_busy; rm -rf "$out"' EXIT

policy=""
for v in OMP_WAIT_POLICY GOMP_SPINCOUNT; do
  [ -n "${!v:-}" ] && policy+="$v=${!v} "
done
echo "wait policy: ${policy:-none set: the ballista default}"
echo "deck: $deck, end_time $END_TIME s; cores: $(nproc); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-6s %-8s %10s %12s  %s\n' "other" "threads" "wall [s]" "Mpsteps/s" "ballista's line"

run_case() {  # $1 = alone|busy, $2 = threads
  local t0 t1 line rate
  t0=$(date +%s.%N)
  line=$("$exe" run "$deck" --no-plots -o "$out/run" --overwrite --threads "$2" \
           --set simulation.end_time="$END_TIME" 2>/dev/null | grep -E '^(completed|FAILED)')
  t1=$(date +%s.%N)
  rate=$(echo "$line" | sed -E 's/.*\(([0-9.e+-]+) particle-steps\/s\).*/\1/')
  awk -v o="$1" -v t="$2" -v a="$t0" -v b="$t1" -v r="$rate" -v l="$line" \
    'BEGIN { printf "%-6s %-8s %10.2f %12.3f  %s\n", o, t, b - a, r / 1e6, l }'
}

for other in alone busy; do
  if [ "$other" = busy ]; then
    yes > /dev/null &
    busy_pid=$!
    sleep 1
  fi
  for r in $(seq "$REPEAT"); do
    for threads in 1 2; do run_case "$other" "$threads"; done
  done
  stop_busy
done
