#!/usr/bin/env bash
# Run the LAMMPS side of the Ballista PD disk-indentation comparison.
#
#   validation/lammps/run_lammps_disk.sh [NP] [NSTEPS] [NTHERMO]
#
#   NP       MPI ranks (default 1).  NP=1 runs lmp directly; NP>1 uses
#            mpirun --allow-run-as-root --oversubscribe -np NP.
#   NSTEPS   time steps (default 1000, the issue's value)
#   NTHERMO  thermo / CSV interval (default 100)
#
# Environment:
#   OUTDIR   where log, screen output and CSV go
#            (default: /tmp/ballista_lammps_disk/npNP)
#
# Installs Debian's LAMMPS (package `lammps`, binary /usr/bin/lmp, Open MPI
# build with the PERI package) if `lmp` is missing, runs pd_disk_indent.in,
# writes the thermo table as CSV and prints throughput
# (atoms x steps / loop wall time).
set -euo pipefail

NP="${1:-1}"
NSTEPS="${2:-1000}"
NTHERMO="${3:-100}"
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
INPUT="$HERE/pd_disk_indent.in"
OUTDIR="${OUTDIR:-/tmp/ballista_lammps_disk/np${NP}}"
mkdir -p "$OUTDIR"

# ---------------------------------------------------------------- install
if ! command -v lmp >/dev/null 2>&1; then
    echo "[lammps] lmp not found: installing Debian package 'lammps'" >&2
    SUDO=""
    if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
    $SUDO apt-get update
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends lammps
fi
LMP="$(command -v lmp)"
LMP_HELP="$("$LMP" -h 2>/dev/null || true)"
if ! grep -q "peri/pmb" <<<"$LMP_HELP"; then
    echo "[lammps] ERROR: $LMP has no pair style peri/pmb (PERI package missing)" >&2
    exit 2
fi
LMP_VERSION="$(sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p' <<<"$LMP_HELP" | head -1)"
PKG_VERSION="$(dpkg-query -W -f='${Version}' lammps 2>/dev/null || echo unknown)"
echo "[lammps] $LMP  (LAMMPS $LMP_VERSION, Debian package $PKG_VERSION)"

# ---------------------------------------------------------------- run
export OMP_NUM_THREADS=1
LOG="$OUTDIR/log.lammps"
SCREEN="$OUTDIR/screen.txt"
cd "$OUTDIR"
if [ "$NP" -gt 1 ]; then
    command -v mpirun >/dev/null 2>&1 || {
        echo "[lammps] ERROR: mpirun not found (Debian: openmpi-bin)" >&2; exit 2; }
    RUN=(mpirun --allow-run-as-root --oversubscribe -np "$NP" "$LMP")
else
    RUN=("$LMP")
fi
echo "[lammps] running: ${RUN[*]} -in $INPUT -var nsteps $NSTEPS -var nthermo $NTHERMO"
"${RUN[@]}" -in "$INPUT" -var nsteps "$NSTEPS" -var nthermo "$NTHERMO" \
    -log "$LOG" -nocite > "$SCREEN" 2>&1 || {
    echo "[lammps] ERROR: LAMMPS failed, tail of $SCREEN:" >&2
    tail -20 "$SCREEN" >&2; exit 1; }

# ---------------------------------------------------------------- CSV
CSV="$OUTDIR/pd_disk_indent_lammps.csv"
# Thermo header written by the input (see thermo_style there):
# Step Time c_ke v_ke_J c_dmean c_dmax v_nbroken v_nbonds0 f_ind
# f_ind[1] f_ind[2] f_ind[3] v_Fy_N v_indy
awk '
  BEGIN { OFS = ","
          print "step,time_s,ke_lammps,ke_J,damage_mean,damage_max,broken_bonds,bonds_initial," \
                "indenter_energy,indenter_fx,indenter_fy,indenter_fz,indenter_fy_N,indenter_y_m" }
  /^ *Step Time c_ke/ { on = 1; next }
  /^Loop time of/     { on = 0 }
  on && NF == 14 && $1 ~ /^[0-9]+$/ { $1 = $1; print }
' "$LOG" > "$CSV"
echo "[lammps] thermo table -> $CSV"
column -s, -t < "$CSV" 2>/dev/null || cat "$CSV"

# ---------------------------------------------------------------- throughput
LOOP_LINE="$(grep -m1 '^Loop time of' "$LOG")"
CPU_LINE="$(grep -m1 'CPU use with' "$LOG" || true)"
BONDS="$(sed -n 's/^ *total # of bonds = //p' "$LOG" | head -1)"
NEIGH="$(sed -n 's/^Ave neighs\/atom = //p' "$LOG" | head -1)"
echo "[lammps] $LOOP_LINE"
echo "[lammps] $CPU_LINE"
echo "[lammps] PD partner entries (each bond counted at both ends): $BONDS; neighbor-list Ave neighs/atom: $NEIGH"
echo "$LOOP_LINE" | awk -v cpu="$CPU_LINE" -v bonds="$BONDS" '{
    t = $4; np = $6; steps = $9; atoms = $12
    ps = atoms * steps / t
    split(cpu, c, "%"); f = c[1] / 100.0
    printf "[lammps] throughput: %.4g particle-steps/s on %d rank(s)  (%d atoms x %d steps / %.4g s)\n", ps, np, atoms, steps, t
    if (bonds != "") printf "[lammps]             %.4g bond evaluations/s (partner entries x steps / s; unique bonds/s = half)\n", bonds * steps / t
    if (f > 0) printf "[lammps] CPU use %.1f%% of %d core(s): CPU-normalised %.4g particle-steps/s per fully used rank-set\n", 100 * f, np, ps / f
}'
