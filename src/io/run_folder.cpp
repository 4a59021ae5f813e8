#include "io/run_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <system_error>
#include <vector>

#include "core/error.hpp"

namespace ballista {

namespace {

namespace fs = std::filesystem;


/// The manifests of the folders this process holds, by absolute folder path.
struct HeldFolder {
  int fd = -1;
  std::set<std::string> names;
};
std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}
std::map<std::string, HeldFolder>& registry() {
  static std::map<std::string, HeldFolder> r;
  return r;
}

std::string normal_absolute(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  std::string s = (ec ? fs::path(path) : p).lexically_normal().string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s;
}

void write_all(int fd, const std::string& text) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(std::string("cannot write the results folder's manifest: ") + std::strerror(errno));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

std::string read_all(int fd) {
  std::string text;
  char buf[4096];
  ::lseek(fd, 0, SEEK_SET);
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

/// A manifest line names a file inside the folder: relative, without `..`.
bool safe_relative(const std::string& rel) {
  if (rel.empty() || rel.front() == '/') return false;
  for (const auto& part : fs::path(rel))
    if (part == "..") return false;
  return true;
}

/// The file names a manifest lists (comment lines and unsafe names skipped).
std::vector<std::string> manifest_names(const std::string& text) {
  std::vector<std::string> names;
  std::size_t from = 0;
  while (from < text.size()) {
    std::size_t end = text.find('\n', from);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(from, end - from);
    from = end + 1;
    if (!line.empty() && line[0] != '#' && safe_relative(line)) names.push_back(std::move(line));
  }
  return names;
}

/// Removes `path` if it is a regular file; true if it was removed.
bool remove_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(path, ec))) return false;
  if (!fs::remove(path, ec) || ec)
    throw Error("cannot remove '" + path.string() + "' of an earlier run: " + ec.message());
  return true;
}

/// The file names Ballista writes (docs/deck.md, Outputs), for a folder without a manifest that
/// the user asked to overwrite.
bool is_ballista_name(const std::string& name, const std::string& folder) {
  static const std::regex results(
      R"((particles_\d+\.h5|particles\.xdmf|history\.csv|summary\.json|resolved\.yaml|penetration\.csv|)"
      R"(channel\.csv|fragments\.csv|penetration_depth\.png|penetration_rate\.png|penetrator_energy\.png|)"
      R"(channel_profile\.png|fragment_mass_distribution\.png|fragment_velocity\.png|fragment_count\.png)(\.tmp)?)");
  static const std::regex tracks(R"(particle_\d+(_history)?\.csv(\.tmp)?)");
  static const std::regex checkpoints(R"(checkpoint_\d+\.h5(\.tmp)?)");
  if (folder == "tracks") return std::regex_match(name, tracks);
  if (folder == "checkpoints") return std::regex_match(name, checkpoints);
  return std::regex_match(name, results);
}

int remove_ballista_names(const fs::path& dir) {
  int removed = 0;
  for (const char* sub : {"", "tracks", "checkpoints"}) {
    const fs::path folder = dir / sub;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) continue;
    std::vector<fs::path> doomed;
    for (const auto& e : fs::directory_iterator(folder, ec))
      if (e.is_regular_file(ec) && is_ballista_name(e.path().filename().string(), sub)) doomed.push_back(e.path());
    for (const auto& p : doomed) removed += remove_file(p) ? 1 : 0;
  }
  return removed;
}

/// The first entry of a folder other than the manifest, or "" if it is empty.
std::string first_entry(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().filename() != kRunManifest) return e.path().filename().string();
  return {};
}

std::string now_text() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace

RunFolder::RunFolder(const std::string& dir, Mode mode, bool overwrite) : dir_(dir), root_(normal_absolute(dir)) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create the results folder '" + dir + "': " + ec.message());
  const fs::path manifest = fs::path(dir) / kRunManifest;
  const bool had_manifest = fs::exists(manifest, ec);
  // A folder an older Ballista wrote (no manifest): its file names are known.
  const bool legacy = !had_manifest && fs::exists(fs::path(dir) / "resolved.yaml", ec) &&
                      (fs::exists(fs::path(dir) / "history.csv", ec) || fs::exists(fs::path(dir) / "summary.json", ec));
  if (mode == Mode::NewRun && !had_manifest && !legacy && !overwrite) {
    if (const std::string other = first_entry(dir); !other.empty())
      throw Error("the results folder '" + dir + "' is not empty and holds no Ballista run (it has '" + other +
                  "'): give a new or empty folder with -o, or --overwrite to write into it anyway (Ballista then "
                  "replaces only the files it writes itself)");
  }
  manifest_ = manifest.string();
  fd_ = ::open(manifest.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error("cannot open '" + manifest.string() + "': " + std::strerror(errno));
  // No waiting: a second run started while the first lives must not run after it and replace its
  // results. (A run killed a moment ago releases the lock when its process is gone.)
  const int err = ::flock(fd_, LOCK_EX | LOCK_NB) == 0 ? 0 : errno;
  if (err != 0) {
    std::string holder = read_all(fd_);
    holder = holder.substr(0, holder.find('\n'));
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK)
      throw Error("the results folder '" + dir + "' is in use by another Ballista run" +
                  (holder.rfind("# ", 0) == 0 ? " (" + holder.substr(2) + ")" : std::string()) +
                  ": wait for it to end, or give another folder with -o");
    throw Error("cannot lock the results folder '" + dir + "': " + std::strerror(err));
  }
  HeldFolder held;
  held.fd = fd_;
  if (mode == Mode::Continue) {
    for (const std::string& name : manifest_names(read_all(fd_))) held.names.insert(name);
    ::lseek(fd_, 0, SEEK_END);
    write_all(fd_, "# continued by pid " + std::to_string(::getpid()) + " at " + now_text() + "\n");
  }
  {
    const std::lock_guard<std::mutex> lock(registry_mutex());
    registry()[root_] = std::move(held);
  }
  if (mode != Mode::NewRun) return;
  try {
    removed_ = clear();
    if (!had_manifest && (overwrite || legacy)) removed_ += remove_ballista_names(dir);
  } catch (...) {
    release();
    throw;
  }
}

void RunFolder::release() {
  {
    const std::lock_guard<std::mutex> lock(registry_mutex());
    registry().erase(root_);
  }
  if (fd_ >= 0) ::close(fd_);  // releases the lock
  fd_ = -1;
}

int RunFolder::clear() {
  int removed = 0;
  for (const std::string& name : manifest_names(read_all(fd_))) {
    removed += remove_file(fs::path(dir_) / name) ? 1 : 0;
    remove_file(fs::path(dir_) / (name + ".tmp"));
  }
  if (::ftruncate(fd_, 0) != 0) throw Error("cannot reset '" + manifest_ + "': " + std::strerror(errno));
  ::lseek(fd_, 0, SEEK_SET);
  write_all(fd_, "# ballista run of pid " + std::to_string(::getpid()) + " started " + now_text() +
                     "\n# the files below are the run's; the next run into this folder removes them\n");
  const std::lock_guard<std::mutex> lock(registry_mutex());
  registry()[root_].names.clear();
  return removed;
}

RunFolder::~RunFolder() { release(); }

void note_output_file(const std::string& path) {
  const std::lock_guard<std::mutex> lock(registry_mutex());
  if (registry().empty()) return;
  const std::string abs = normal_absolute(path);
  for (auto& [root, held] : registry()) {
    if (abs.size() <= root.size() + 1 || abs.compare(0, root.size(), root) != 0 || abs[root.size()] != '/') continue;
    const std::string rel = abs.substr(root.size() + 1);
    if (held.names.insert(rel).second) write_all(held.fd, rel + "\n");
    return;
  }
}

}  // namespace ballista
