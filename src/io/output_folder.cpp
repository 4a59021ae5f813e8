#include "io/output_folder.hpp"

#include <filesystem>
#include <regex>
#include <system_error>

#include "core/error.hpp"

namespace ballista {

namespace {

/// Names `ballista run` writes into a results folder (docs/deck.md, Outputs).
bool is_run_output(const std::string& name) {
  static const std::regex pattern(
      R"((particles_\d+\.h5|particles\.xdmf|history\.csv|summary\.json|resolved\.yaml|penetration\.csv|)"
      R"(channel\.csv|fragments\.csv|penetration_depth\.png|penetration_rate\.png|penetrator_energy\.png|channel_profile\.png)"
      R"(|fragment_mass_distribution\.png|fragment_velocity\.png|fragment_count\.png)"
      R"(|.*\.tmp))");
  return std::regex_match(name, pattern);
}

enum class Folder { Results, Tracks, Checkpoints };

int remove_matching(const std::filesystem::path& dir, Folder folder) {
  namespace fs = std::filesystem;
  int removed = 0;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec)) continue;
    const std::string name = e.path().filename().string();
    const std::string ext = e.path().extension().string();
    bool match = false;
    switch (folder) {
      case Folder::Results: match = is_run_output(name); break;
      case Folder::Tracks: match = (name.rfind("particle_", 0) == 0 && ext == ".csv") || ext == ".tmp"; break;
      case Folder::Checkpoints: match = (name.rfind("checkpoint_", 0) == 0 && ext == ".h5") || ext == ".tmp"; break;
    }
    if (!match) continue;
    if (!fs::remove(e.path(), ec) || ec)
      throw Error("cannot remove '" + e.path().string() + "' of an earlier run: " + ec.message());
    ++removed;
  }
  return removed;
}

}  // namespace

int prepare_run_folder(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create the results folder '" + dir + "': " + ec.message());
  return remove_matching(dir, Folder::Results) + remove_matching(fs::path(dir) / "tracks", Folder::Tracks) +
         remove_matching(fs::path(dir) / "checkpoints", Folder::Checkpoints);
}

}  // namespace ballista
