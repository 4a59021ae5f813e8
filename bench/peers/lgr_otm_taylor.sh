#!/usr/bin/env bash
# Peer throughput benchmark: LGR's OTM solver (Sandia LGR v3, github sandialabs/lgrtk master,
# the code behind SAND2020-9716 ch. 3) on the copper Taylor bar of examples/taylor_bar_otm.yaml.
#
#   bench/peers/lgr_otm_taylor.sh LGR_SRC [BUILD_DIR=/tmp/lgr-build]
#
# Measures: wall time of LGR's otm_run() (explicit OTM steps: LME shape functions, J2 update,
# ArborX neighbour searches, stable-dt, wall contact) for a fixed simulated time, 1 thread
# (Kokkos Serial), no file output; prints points, nodes, steps, wall s, point-steps/s per size.
# Set-up (Exodus read, tet-to-meshless conversion, initial support search) is timed separately.
#
# Limits / differences from Ballista's problem:
#  * LGR's OTM is 3-D only: the bar is a full 3-D cylinder (R 3.2 mm, L 32.4 mm) of linear tets,
#    one material point per tet (LGR's otm_taylor set-up), nodes = tet vertices; Ballista's run
#    is 2-D axisymmetric on a grid, so "points" are not equivalent resolution-wise.
#  * The tet mesh is ours (bench/peers/lgr_cylinder_exo.cpp: square grid mapped to the disk,
#    6 tets per hex), not the unpublished cylinder.g of LGR's app.
#  * Material set to Ballista's (rho 8930, E 117 GPa, nu 0.35, Y0 400 MPa, linear H 100 MPa via
#    LGR's power law with n = 1); LGR numerics kept (gamma 1.5, >= 12 support nodes, CFL 0.1,
#    displacement wall at z = 0). Only a few steps are run: a throughput test, not a validation.
#  * LGR's OTM needs ArborX + Kokkos. Debian 12 has Kokkos 3.4 (libtrilinos-kokkos-dev) but not
#    ArborX; LGR uses the device-templated BVH API, which only ArborX <= v0.9-beta provides
#    (v1.0/v1.1 keep it in name but it does not match). Give an ArborX v0.9-beta source tree in
#    ARBORX_SRC, or an installed one via ARBORX_DIR (dir holding ArborXConfig.cmake).
#    Exodus: Debian libexodusii-dev (a small CMake shim stands in for SEACASExodus).
#  * Nothing is downloaded; no LGR code is copied. Env: LGR_SIZES ("N_ACROSS ..."; default
#    "6 8 12"), LGR_END_TIME (default 3e-8 s), LGR_JOBS (default 2).
set -euo pipefail

LGR_SRC=$(realpath "${1:?usage: $0 LGR_SRC [BUILD_DIR]}")
BUILD=${2:-/tmp/lgr-build}
HERE=$(cd "$(dirname "$0")" && pwd)
SIZES=${LGR_SIZES:-"6 8 12"}
END_TIME=${LGR_END_TIME:-3e-8}
JOBS=${LGR_JOBS:-2}
R=3.2e-3
L=32.4e-3
mkdir -p "$BUILD"
BUILD=$(realpath "$BUILD")

[ -f "$LGR_SRC/otm_apps.cpp" ] || { echo "no LGR OTM sources in $LGR_SRC" >&2; exit 1; }
for f in /usr/include/trilinos/Kokkos_Core.hpp /usr/include/exodusII.h; do
  [ -f "$f" ] || { echo "missing $f: apt-get install libtrilinos-kokkos-dev libexodusii-dev" >&2; exit 1; }
done

# --- ArborX (header-only; installed into the build dir) ---
if [ -z "${ARBORX_DIR:-}" ]; then
  [ -n "${ARBORX_SRC:-}" ] && [ -f "$ARBORX_SRC/CMakeLists.txt" ] ||
    { echo "set ARBORX_SRC (ArborX v0.9-beta source) or ARBORX_DIR" >&2; exit 1; }
  if [ ! -f "$BUILD/arborx-install/lib/cmake/ArborX/ArborXConfig.cmake" ]; then
    nice -n 19 cmake -S "$ARBORX_SRC" -B "$BUILD/arborx-build" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_INSTALL_PREFIX="$BUILD/arborx-install" -DARBORX_ENABLE_TESTS=OFF \
      -DARBORX_ENABLE_EXAMPLES=OFF -DARBORX_ENABLE_BENCHMARKS=OFF -DARBORX_ENABLE_MPI=OFF >/dev/null
    nice -n 19 cmake --build "$BUILD/arborx-build" --target install >/dev/null
  fi
  ARBORX_DIR="$BUILD/arborx-install/lib/cmake/ArborX"
fi
ARBORX_INC=$(realpath "$ARBORX_DIR/../../../include")

# --- CMake shims: Exodus as SEACASExodus; Debian's KokkosConfig points at /usr/lib/include ---
SHIM="$BUILD/shim"
mkdir -p "$SHIM"
cat >"$SHIM/SEACASExodusConfig.cmake" <<'EOF'
find_library(_EXO_LIB exoIIv2c REQUIRED)
find_library(_NETCDF_LIB netcdf REQUIRED)
find_path(SEACASExodus_INCLUDE_DIRS exodusII.h REQUIRED)
if(NOT TARGET exodus)
  add_library(exodus UNKNOWN IMPORTED)
  set_target_properties(exodus PROPERTIES IMPORTED_LOCATION "${_EXO_LIB}"
    INTERFACE_INCLUDE_DIRECTORIES "${SEACASExodus_INCLUDE_DIRS}" INTERFACE_LINK_LIBRARIES "${_NETCDF_LIB}")
endif()
set(SEACASExodus_TPL_INCLUDE_DIRS "")
set(SEACASExodus_TPL_LIBRARIES "${_NETCDF_LIB}")
set(SEACASExodus_FOUND TRUE)
EOF
cat >"$SHIM/kokkos_fix.cmake" <<'EOF'
if(NOT TARGET Kokkos::kokkos)
  add_library(Kokkos::kokkos INTERFACE IMPORTED)
  set_target_properties(Kokkos::kokkos PROPERTIES
    INTERFACE_LINK_LIBRARIES "trilinos_kokkosalgorithms;trilinos_kokkoscontainers;trilinos_kokkoscore"
    INTERFACE_COMPILE_FEATURES "cxx_std_14"
    INTERFACE_INCLUDE_DIRECTORIES "/usr/include/trilinos")
endif()
EOF

# --- LGR (out of tree, CPU only, Release; GCC 12 warnings must not be fatal) ---
nice -n 19 cmake -S "$LGR_SRC" -B "$BUILD/lgr" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG -Wno-error" -DLGR_ENABLE_CUDA=OFF \
  -DLGR_ENABLE_UNIT_TESTS=OFF -DLGR_ENABLE_SEARCH=ON -DLGR_ENABLE_EXODUS=ON \
  -DArborX_DIR="$ARBORX_DIR" -DSEACASExodus_DIR="$SHIM" \
  -DCMAKE_PROJECT_INCLUDE="$SHIM/kokkos_fix.cmake" >"$BUILD/lgr-configure.log"
nice -n 19 cmake --build "$BUILD/lgr" -j "$JOBS" --target lgrlib >"$BUILD/lgr-build.log"

# --- project helpers: mesh writer and timing driver (link against lgrlib) ---
nice -n 19 g++ -O2 -o "$BUILD/lgr_cylinder_exo" "$HERE/lgr_cylinder_exo.cpp" -lexoIIv2c -lnetcdf
nice -n 19 g++ -std=c++14 -O3 -DNDEBUG -DLGR_ENABLE_EXODUS -DLGR_ENABLE_SEARCH -I"$LGR_SRC" \
  -isystem "$ARBORX_INC" -isystem "$ARBORX_INC/details" -isystem /usr/include/trilinos \
  "$HERE/lgr_otm_taylor_driver.cpp" -o "$BUILD/lgr_otm_taylor_driver" "$BUILD/lgr/liblgr.a" \
  -lexoIIv2c -lnetcdf -ltrilinos_kokkosalgorithms -ltrilinos_kokkoscontainers -ltrilinos_kokkoscore -ldl

# --- runs ---
export OMP_NUM_THREADS=1
printf '%-8s %8s %7s %8s %6s %9s %9s %14s\n' n_across points nodes support steps setup_s wall_s point_steps/s
for n in $SIZES; do
  nz=$(awk -v n="$n" -v l="$L" -v r="$R" 'BEGIN { printf "%d", n * l / (2 * r) + 0.5 }')
  mesh="$BUILD/cylinder_${n}.g"
  "$BUILD/lgr_cylinder_exo" "$mesh" "$R" "$L" "$n" "$nz" >/dev/null
  line=$("$BUILD/lgr_otm_taylor_driver" "$mesh" "$END_TIME" | grep '^RESULT')
  echo "$line" | awk -v n="$n" '{ for (i = 2; i < NF; i += 2) v[$i] = $(i + 1);
    printf "%-8s %8d %7d %8.1f %6d %9.2f %9.2f %14.0f\n", n, v["points"], v["nodes"],
      v["avg_support"], v["steps"], v["setup_s"], v["run_s"], v["point_steps_per_s"] }'
done
