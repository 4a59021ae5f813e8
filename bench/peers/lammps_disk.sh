#!/bin/sh
# Ballista beside LAMMPS PERI (Debian's `lammps`, installed by validation/lammps/run_lammps_disk.sh
# if absent) on the disk-indentation problem: examples/pd_disk_indent.yaml against
# validation/lammps/pd_disk_indent.in, the same 105,525-point PMB disk, indenter, contact and
# fracture, 1000 steps. The two codes run alternately, LAMMPS on 1 and 2 MPI ranks, Ballista on 1
# and 2 threads, ROUNDS times, so that both see the same machine state; a ratio from one code run
# in another hour does not count (docs/performance.md).
#
#   bench/peers/lammps_disk.sh [BALLISTA_BINARY] [WORK_DIR]        (ROUNDS=2 STEPS=1000 by default)
#
# Each code's rate is point-steps per second of its time-step loop: LAMMPS's "Loop time of T on P
# procs for S steps with N atoms" (its set-up, the bond families included, is outside the loop),
# Ballista's summary.json statistics.particle_steps_per_second (the step loop; the bond families
# are built before it). One line per run and a ratio per pair.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
ballista=${1:-$root/build/ballista}
work=${2:-/tmp/ballista_lammps_peer}
rounds=${ROUNDS:-2}
steps=${STEPS:-1000}
mkdir -p "$work"

lammps_rate() {  # ranks -> point-steps/s
  OUTDIR="$work/lammps_np$1" "$root/validation/lammps/run_lammps_disk.sh" "$1" "$steps" 100 >/dev/null 2>&1 ||
    { echo "LAMMPS failed: $work/lammps_np$1" >&2; exit 1; }
  sed -n 's/^Loop time of \([0-9.e+-]*\) on \([0-9]*\) procs for \([0-9]*\) steps with \([0-9]*\) atoms.*/\1 \3 \4/p' \
    "$work/lammps_np$1/log.lammps" | tail -1 | awk '{ printf "%.6g", $2 * $3 / $1 }'
}

ballista_rate() {  # threads -> point-steps/s
  OMP_WAIT_POLICY=passive "$ballista" run "$root/examples/pd_disk_indent.yaml" -o "$work/ballista_t$1" -q \
    --no-plots --overwrite --threads "$1" --set simulation.max_steps="$steps" >/dev/null 2>&1 ||
    { echo "Ballista failed: $work/ballista_t$1" >&2; exit 1; }
  /usr/bin/python3 -c 'import json, sys
print("%.6g" % json.load(open(sys.argv[1]))["statistics"]["particle_steps_per_second"])' "$work/ballista_t$1/summary.json"
}

r=1
while [ "$r" -le "$rounds" ]; do
  for cores in 1 2; do
    if [ $((r % 2)) -eq 1 ]; then  # alternate which code goes first
      l=$(lammps_rate "$cores"); b=$(ballista_rate "$cores")
    else
      b=$(ballista_rate "$cores"); l=$(lammps_rate "$cores")
    fi
    printf 'round %s, %s core(s): LAMMPS %.3g point-steps/s (%s rank(s)), Ballista %.3g (%s thread(s)): ratio %.2f\n' \
      "$r" "$cores" "$l" "$cores" "$b" "$cores" "$(awk -v a="$b" -v b="$l" 'BEGIN { print a / b }')"
  done
  r=$((r + 1))
done
