#!/bin/bash
# The exploding cylinder example as it was in BASE (0.86 mm case and products, gas family fixed,
# 25 us: the example of the milestone's first build, 0f0a342, which cannot read today's example) run
# by BASE's build and by this tree's, in turn, over ROUNDS rounds (the first a warm-up: quote the
# others), 2 threads, one machine. docs/performance.md, "The exploding cylinder with the
# peridynamic gas".
#   bench/exploding_cylinder_vs_base.sh BASE_CHECKOUT [ROUNDS] [THIS_CHECKOUT]
# Each checkout must have build/ballista. Prints one wall time per run.
set -e
B=${1:?the base checkout (with build/ballista)}; R=${2:-4}; N=${3:-$(cd "$(dirname "$0")/.." && pwd)}
deck=$(mktemp /tmp/cyl_base_XXXXXX.yaml)
git -C "$B" show HEAD:examples/exploding_cylinder_pd.yaml > "$deck"
for r in $(seq 1 "$R"); do
  for k in base this; do
    if [ "$k" = base ]; then bin="$B/build/ballista"; else bin="$N/build/ballista"; fi
    rm -rf "/tmp/cylab_$k"  # older builds take no --overwrite
    /usr/bin/time -f "round $r $k %e s" "$bin" run "$deck" -o "/tmp/cylab_$k" -q --no-plots --threads 2 2>&1 | tail -1
  done
done
rm -f "$deck"
