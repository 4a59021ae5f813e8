#include "core/data_dir.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#ifndef BALLISTA_SOURCE_DIR
#define BALLISTA_SOURCE_DIR "."
#endif

namespace ballista {

namespace fs = std::filesystem;

namespace {

struct DataDir {
  std::string path, origin;
};

/// <prefix>/share/ballista if the executable sits in <prefix>/bin and the presets are there.
std::string installed_data_dir() {
  const std::string exe = executable_path();
  if (exe.empty()) return {};
  const fs::path bin = fs::path(exe).parent_path();
  if (bin.filename() != "bin") return {};
  const fs::path share = bin.parent_path() / "share" / "ballista";
  std::error_code ec;
  return fs::exists(share / "data" / "materials.yaml", ec) ? share.string() : std::string{};
}

DataDir find_data_dir() {
  if (const char* env = std::getenv(kDataDirEnv); env && *env) return {env, "environment"};
  if (std::string installed = installed_data_dir(); !installed.empty()) return {installed, "installed"};
  return {BALLISTA_SOURCE_DIR, "source tree"};
}

}  // namespace

std::string executable_path() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string{} : exe.string();
}

std::string data_dir() { return find_data_dir().path; }

std::string data_dir_origin() { return find_data_dir().origin; }

}  // namespace ballista
