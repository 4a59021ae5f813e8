# Sourced by the MPI benchmarks (bench/mpi_block_impact.sh, bench/mpi_pd_cube.sh).
# run_case EXE DECK RANKS THREADS STEPS DIR: one `ballista run` of DECK stopped after STEPS steps
# (simulation.max_steps), plain on one rank, under mpirun on several; output to DIR.
run_case() {
  local exe=$1 deck=$2 ranks=$3 threads=$4 steps=$5 dir=$6
  if [ "$ranks" = 1 ]; then
    "$exe" run "$deck" -o "$dir" -q --no-plots --threads "$threads" --set simulation.max_steps="$steps" >/dev/null 2>&1
  else
    mpirun --oversubscribe --allow-run-as-root -np "$ranks" "$exe" run "$deck" -o "$dir" -q --no-plots \
      --threads "$threads" --set simulation.max_steps="$steps" >/dev/null 2>&1
  fi
}
