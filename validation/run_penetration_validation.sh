#!/usr/bin/env bash
# Penetration validation studies of docs/validation.md ("Penetration"), thesis seed 000 ch. 5-6:
#   velocity    U against V (Orphal-Anderson U = a + bV, thesis Figs. 5.11-5.12)   ballista sweep
#   density     depth against rod density at fixed mass (thesis Table 5.3)         ballista run x5
#   confinement depth against confinement, drained and saturated (Table 5.5)       ballista sweep
#   segmented   solid against segmented rod into the 4130 billet (Table 6.5)       ballista sweep
#   resolution  grid convergence of depth and rate, 2 / 1 / 0.5 mm (~15 min)       ballista sweep
# then summarise.py writes validation_summary.md (the tables of docs/validation.md).
# Usage: validation/run_penetration_validation.sh [BUILD_DIR] [OUT_DIR] [study ...]
# About 40 minutes on 2 cores for all studies.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
out=${2:-out/validation}
shift $(( $# > 2 ? 2 : $# )) || true
studies=${*:-velocity density confinement segmented resolution}
bin="$build/ballista"
deck="$here/rod_sandstone_reduced.yaml"
mkdir -p "$out"
failed=0
# A study whose runs fail is reported (the summary shows the missing values) and the rest go on.
note() { echo "study $1: a run failed (see its folder)" >&2; failed=1; }
for s in $studies; do
  case $s in
    velocity)
      "$bin" sweep "$deck" -o "$out/velocity" --vary bodies.1.rod.speed=1500,2100,2700,3300,3900 --set simulation.end_time=40e-6 || note velocity ;;
    density)
      # Mass held at that of the 19.235 g/cm^3, 24 mm rod: L = 24 mm x 19235 / rho (Table 5.3 rows).
      # The target grows downwards to 150 mm (the lightest, longest rod reaches ~95 mm) and the
      # grid upwards to hold the longest rod.
      for rho in 9618 14426 19235 24044 38470; do
        len=$(/usr/bin/python3 -c "print(24.0e-3 * 19235 / $rho)")
        top=$(/usr/bin/python3 -c "print(0.091 + $len + 4e-3)")
        "$bin" run "$deck" -q -o "$out/density/rho_$rho" --set materials.rod.density=$rho \
          --set bodies.1.rod.length=$len --set grid.upper=[30.0e-3,$top] --set grid.lower=[0,-0.065] \
          --set bodies.0.shape.center=[0,-0.06] --set bodies.0.shape.length=0.15 --set simulation.end_time=80e-6 \
          || note density
      done ;;
    confinement)
      "$bin" sweep "$deck" -o "$out/confinement" \
        --vary materials.rock.preset=sandstone_berea_drained,sandstone_berea_saturated \
        --vary loads.0.pressure=0,34.48e6,103.4e6 \
        --set simulation.end_time=150e-6 || note confinement ;;  # the unconfined rods still go at 60 us
    segmented)
      "$bin" sweep "$here/../examples/rod_billet_4130_mpm.yaml" -o "$out/segmented" --vary bodies.1.rod.segment_ld=0,0.5 || note segmented ;;
    resolution)
      "$bin" sweep "$deck" -o "$out/resolution" --vary grid.cell_size=2e-3,1e-3,0.5e-3 || note resolution ;;
    *) echo "unknown study '$s' (velocity, density, confinement, segmented, resolution)" >&2; exit 2 ;;
  esac
done
/usr/bin/python3 "$here/summarise.py" "$out" > "$out/validation_summary.md"
cat "$out/validation_summary.md"
exit $failed
