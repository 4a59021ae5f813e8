#!/bin/sh
# Ballista beside Karamelo (C++/MPI MPM, https://github.com/adevaucorbeil/karamelo), issue 17
# item 2: the 3D copper Taylor bar of Karamelo's examples/Taylor-bar/cylindrical/ULMPM at the same
# size in both codes (full cylinder R 3.8 mm, L 25.4 mm, 190 m/s, 0.25 mm cells, one particle per
# cell = 74,664 particles, linear, MUSL (Karamelo's ULMPM with FLIP 0.99), Johnson-Cook + shock
# EOS). Each code runs W and W + S steps; the difference removes the setup, so the rate is that
# of S steady steps: particles x S / (t(W + S) - t(W)). Karamelo runs on 1 and 2 MPI ranks,
# Ballista on 1 and 2 threads, alternately.
#
#   bench/peers/karamelo_taylor.sh KARAMELO_SOURCE [BALLISTA_BINARY] [WORK_DIR]
#
# KARAMELO_SOURCE is a checkout the user provides (nothing is downloaded); it is built into
# WORK_DIR/karamelo-build (Release, with Debian's Eigen 3 and Open MPI). The figures and the
# exact command are recorded in docs/performance.md.
set -eu
src=${1:?usage: karamelo_taylor.sh KARAMELO_SOURCE [BALLISTA_BINARY] [WORK_DIR]}
here=$(cd "$(dirname "$0")" && pwd)
ballista=${2:-$here/../../build/ballista}
work=${3:-/tmp/ballista_karamelo_peer}
warm=${WARM_STEPS:-20}
steady=${STEADY_STEPS:-200}
particles=74664
mkdir -p "$work"

if [ ! -x "$work/karamelo-build/karamelo" ]; then
  echo "building Karamelo from $src into $work/karamelo-build ..."
  cmake -S "$src" -B "$work/karamelo-build" -DCMAKE_BUILD_TYPE=Release >"$work/karamelo-cmake.log" 2>&1
  cmake --build "$work/karamelo-build" -j 2 >"$work/karamelo-build.log" 2>&1 ||
    { echo "Karamelo did not build: $work/karamelo-build.log" >&2; exit 1; }
fi
karamelo=$work/karamelo-build/karamelo

# Karamelo's input: its ULMPM Taylor-bar example's physics and size, output switched off, run for
# $1 steps in total (one step, then the wall condition, then the rest, as the example does).
karamelo_deck() {
  cat <<EOF
E = 115
nu = 0.31
K = E/(3*(1-2*nu))
G = E/(2*(1+nu))
rho = 8.94e-06
hLx = 25.4/2
R = 3.8
Df = 15.0/2
Tr = 25
method(ulmpm, FLIP, linear, 0.99)
N = 4
cellsize = 1/N
x_wall = hLx + 3*cellsize
dimension(3, -hLx, x_wall, -Df, Df, -Df, Df, cellsize)
eos(eoss, shock, rho, K, 3933, 1.5, 0, 0, Tr, 0, 0)
strength(strengthJC, johnson_cook, G, 0.065, 0.356, 0.37, 1e-3, 0, 0, Tr, 1600)
material(mat, eos-strength, eoss, strengthJC)
region(cyl, cylinder, x, 0, 0, R, -hLx, hLx)
solid(solid1, region, cyl, 1, mat, cellsize, Tr)
region(region2, block, x_wall - cellsize, INF, INF, INF, INF, INF)
group(groupn2, nodes, region, region2, solid, solid1)
group(gBall1, particles, region, cyl, solid, solid1)
fix(v0Ball1, initial_velocity_particles, gBall1, 190, NULL, NULL)
set_output(1000000)
dt_factor(0.25)
log_modify(custom, step, dt, time)
run(1)
fix(BC_Wall, velocity_nodes, groupn2, 0, NULL, NULL)
run($(($1 - 1)))
EOF
}

now() { date +%s.%N; }
# Wall seconds of a command.
timed() {
  t0=$(now)
  "$@" >/dev/null 2>&1 || { echo "failed: $*" >&2; exit 1; }
  t1=$(now)
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.6f", b - a }'
}

rate() {  # particle-steps per second from the two wall times
  awk -v n="$particles" -v s="$steady" -v a="$1" -v b="$2" 'BEGIN { printf "%.6g", n * s / (b - a) }'
}

karamelo_run() {  # ranks steps
  karamelo_deck "$2" >"$work/taylor_$2.mpm"
  (cd "$work" && timed mpirun --oversubscribe --allow-run-as-root -np "$1" "$karamelo" -i "taylor_$2.mpm")
}

ballista_run() {  # threads steps
  timed env OMP_WAIT_POLICY=passive "$ballista" run "$here/karamelo_taylor_ballista.yaml" -o "$work/ballista_$2" -q \
    --no-plots --threads "$1" --set simulation.max_steps="$2"
}

for cores in 1 2; do
  k0=$(karamelo_run "$cores" "$warm")
  b0=$(ballista_run "$cores" "$warm")
  k1=$(karamelo_run "$cores" $((warm + steady)))
  b1=$(ballista_run "$cores" $((warm + steady)))
  kr=$(rate "$k0" "$k1")
  br=$(rate "$b0" "$b1")
  printf '%s core(s): Karamelo %.3g particle-steps/s (%s rank(s)), Ballista %.3g (%s thread(s)): ratio %.2f\n' \
    "$cores" "$kr" "$cores" "$br" "$cores" "$(awk -v a="$br" -v b="$kr" 'BEGIN { print a / b }')"
done
