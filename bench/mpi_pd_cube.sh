#!/usr/bin/env bash
# MPI benchmark of peridynamics (issue 16, docs/performance.md "Several ranks"): the 50^3 glass cube
# of bench/pd_cube_bench.yaml (125,000 points, m = 3, ~114 bond ends per point, PMB, flying at
# 10 m/s), run by the real `ballista run` on 1 rank x 1 thread, 1 rank x 2 threads, 2 ranks x 1
# thread (and more if CASES says so).
#
# Throughput is marginal: each case runs STEPS_SHORT and STEPS_LONG steps (simulation.max_steps)
# and reports (point-steps of the long run - of the short run) / (wall difference), so seeding,
# the bond families, the partition and the ghosts at the start cancel out. Bond evaluations per
# second count each bond once (bond ends / 2 per point-step: bytes_per_bond_end aside, the
# summary's mean bond count). The halo bytes and messages per step on rank 0 come from summary.json.
#
#   bench/mpi_pd_cube.sh [BUILD_DIR]
# Environment: STEPS_SHORT (default 20), STEPS_LONG (120), CASES (default "1x1 1x2 2x1").
set -euo pipefail

BUILD=${1:-build}
STEPS_SHORT=${STEPS_SHORT:-20}
STEPS_LONG=${STEPS_LONG:-120}
CASES=${CASES:-"1x1 1x2 2x1"}
exe="$BUILD/ballista"
deck="$(dirname "$0")/pd_cube_bench.yaml"
[ -x "$exe" ] || { echo "no $exe (make build)" >&2; exit 1; }
PY=/usr/bin/python3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
BOND_ENDS_PER_POINT=113.8  # the cube's mean family size (docs/performance.md, peridynamics throughput)

# shellcheck source=bench/mpi_run_case.sh
source "$(dirname "$0")/mpi_run_case.sh"

echo "peridynamic cube, 125,000 points, marginal throughput over steps $STEPS_SHORT..$STEPS_LONG"
printf "%-16s %14s %16s %14s %16s %14s\n" "ranks x threads" "M p-steps/s" "M bonds/s" "s per step" "halo B/step r0" \
  "msgs/step r0"
for c in $CASES; do
  ranks=${c%x*}; threads=${c#*x}
  run_case "$exe" "$deck" "$ranks" "$threads" "$STEPS_SHORT" "$out/short_$c"
  run_case "$exe" "$deck" "$ranks" "$threads" "$STEPS_LONG" "$out/long_$c"
  $PY - "$out/short_$c/summary.json" "$out/long_$c/summary.json" "$c" "$BOND_ENDS_PER_POINT" <<'PYEOF'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
ps = b["statistics"]["particle_steps"] - a["statistics"]["particle_steps"]
wall = b["statistics"]["wall_time"] - a["statistics"]["wall_time"]
steps = b["statistics"]["steps"] - a["statistics"]["steps"]
sr = b.get("solver_results", {})
bonds = ps * float(sys.argv[4]) / 2.0
print(f"{sys.argv[3]:<16} {ps / wall / 1e6:14.3f} {bonds / wall / 1e6:16.1f} {wall / steps:14.4f} "
      f"{sr.get('halo_bytes_per_step_rank0', 0):16.4g} {sr.get('halo_messages_per_step_rank0', 0):14.3g}")
PYEOF
done
