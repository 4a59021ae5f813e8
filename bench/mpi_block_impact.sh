#!/usr/bin/env bash
# MPI benchmark (issue 16, docs/performance.md "Several ranks"): the 3D J2 steel block of the MPM
# benchmarks (bench/block_impact_deck.hpp: 200 m/s onto a rigid wall, MUSL, FLIP 0.99, linear
# shape functions, 8 particles per cell) at PARTICLES particles, run by the real `ballista run`
# on 1 rank x 1 thread, 1 rank x 2 threads, 2 ranks x 1 thread (and more if RANKS says so).
#
# Throughput is marginal: each case runs STEPS_SHORT and STEPS_LONG steps (simulation.max_steps)
# and reports (particle-steps of the long run - of the short run) / (wall difference), so seeding,
# the first partition and the particle files at the start and the end cancel out. The halo bytes
# and messages per step on rank 0 come from summary.json (solver_results).
#
#   bench/mpi_block_impact.sh [BUILD_DIR]
# The end time (100 us) is never reached: simulation.max_steps ends each run (with a warning).
# Environment: PARTICLES (default 1000000), STEPS_SHORT (10), STEPS_LONG (40), CASES (default
# "1x1 1x2 2x1": ranks x threads).
set -euo pipefail

BUILD=${1:-build}
PARTICLES=${PARTICLES:-1000000}
STEPS_SHORT=${STEPS_SHORT:-10}
STEPS_LONG=${STEPS_LONG:-40}
CASES=${CASES:-"1x1 1x2 2x1"}
exe="$BUILD/ballista"
[ -x "$exe" ] || { echo "no $exe (make build)" >&2; exit 1; }
PY=/usr/bin/python3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# The block_impact_deck of bench/block_impact_deck.hpp, as YAML (same sizes and margins).
$PY - "$PARTICLES" > "$out/deck.yaml" <<'PYEOF'
import math, sys
n = int(sys.argv[1])
nx = round((n / 8.0 / 0.8) ** (1.0 / 3.0)); ny = round(0.8 * nx)
h = 1.0e-3; lx, ly = nx * h, ny * h; m, top = 4 * h, 2 * h
print(f"""simulation: {{solver: mpm, dimension: 3d, end_time: 1.0e-4, cfl: 0.3, on_particle_exit: delete}}
materials:
  steel: {{model: j2_plasticity, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.29,
          yield_stress: 350.0e6, hardening_modulus: 1.0e9}}
mpm: {{shape_function: linear, update: musl, flip: 0.99, sort_every: 20}}
grid:
  lower: [0, 0, 0]
  upper: [{lx + 2 * m!r}, {ly + top!r}, {lx + 2 * m!r}]
  cell_size: {h!r}
  boundary: {{y_min: wall}}
bodies:
  - name: block
    material: steel
    shape: {{type: box, lower: [{m!r}, 0.0, {m!r}], upper: [{m + lx!r}, {ly!r}, {m + lx!r}]}}
    particles_per_cell: 2
    velocity: [0, -200.0, 0]
output:
  fields: [x]
""")
PYEOF

# shellcheck source=bench/mpi_run_case.sh
source "$(dirname "$0")/mpi_run_case.sh"

echo "block impact, $PARTICLES particles, marginal throughput over steps $STEPS_SHORT..$STEPS_LONG"
printf "%-16s %14s %14s %16s %14s\n" "ranks x threads" "M p-steps/s" "s per step" "halo B/step r0" "msgs/step r0"
for c in $CASES; do
  ranks=${c%x*}; threads=${c#*x}
  run_case "$exe" "$out/deck.yaml" "$ranks" "$threads" "$STEPS_SHORT" "$out/short_$c"
  run_case "$exe" "$out/deck.yaml" "$ranks" "$threads" "$STEPS_LONG" "$out/long_$c"
  $PY - "$out/short_$c/summary.json" "$out/long_$c/summary.json" "$c" <<'PYEOF'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
ps = b["statistics"]["particle_steps"] - a["statistics"]["particle_steps"]
wall = b["statistics"]["wall_time"] - a["statistics"]["wall_time"]
steps = b["statistics"]["steps"] - a["statistics"]["steps"]
sr = b.get("solver_results", {})
print(f"{sys.argv[3]:<16} {ps / wall / 1e6:14.3f} {wall / steps:14.4f} {sr.get('halo_bytes_per_step_rank0', 0):16.4g} "
      f"{sr.get('halo_messages_per_step_rank0', 0):14.3g}")
PYEOF
done
