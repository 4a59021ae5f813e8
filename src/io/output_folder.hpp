#pragma once
// Preparing a results folder for a run (issue 11): a second run into the same `-o` folder must
// not leave the first run's particle files beside its own (ParaView and the checks would mix
// them), and a temporary file left by a run killed mid-write must not linger.
#include <string>

namespace ballista {

/// Creates `dir` if needed and removes what an earlier `ballista run` wrote there: particle files
/// (particles_*.h5, particles.xdmf), history.csv, summary.json, resolved.yaml, penetration.csv,
/// channel.csv, the penetration figures, tracks/particle_*.csv, checkpoints/checkpoint_*.h5, and every *.tmp. Other files are
/// left alone. Returns the number of files removed.
int prepare_run_folder(const std::string& dir);

}  // namespace ballista
