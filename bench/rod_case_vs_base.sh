#!/bin/bash
# The thesis-size rod case (examples/rod_sandstone_mpm.yaml to 500 us, 2 threads) timed three ways,
# in rotated order over two rounds on one machine: BASE's build running BASE's own deck (the build
# the speed issue's whole-run target is measured against), this tree's build with one step for all,
# and with mpm.multirate=8. docs/performance.md, "Penetration runs".
#   bench/rod_case_vs_base.sh BASE_CHECKOUT [THIS_CHECKOUT]
# Each checkout must have build/ballista. Prints one wall time per run; the run folders are
# /tmp/rodab_<run> (their summary.json has steps, depth and the update ratio).
set -e
B=${1:?the base checkout (with build/ballista)}; N=${2:-$(cd "$(dirname "$0")/.." && pwd)}
run() {  # label binary deck extra-overrides
  rm -rf "/tmp/rodab_$1"  # older builds take no --overwrite
  /usr/bin/time -f "$1 %e s" "$2" run "$3" -o "/tmp/rodab_$1" -q --no-plots --threads 2 \
      --set simulation.end_time=500e-6 $4 2>&1 | tail -1
}
for r in 1 2; do
  if [ "$r" = 1 ]; then order="base plain mr"; else order="mr base plain"; fi
  for k in $order; do
    case $k in
      base) run "base$r" "$B/build/ballista" "$B/examples/rod_sandstone_mpm.yaml" "" ;;
      plain) run "plain$r" "$N/build/ballista" "$N/examples/rod_sandstone_mpm.yaml" "--set mpm.multirate=none" ;;
      mr) run "mr$r" "$N/build/ballista" "$N/examples/rod_sandstone_mpm.yaml" "--set mpm.multirate=8" ;;
    esac
  done
done
