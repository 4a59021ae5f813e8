#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.hpp"
#include "io/run_folder.hpp"

namespace ballista {

namespace {
std::string errno_text() { return std::strerror(errno); }
}  // namespace

std::string tmp_path_for(const std::string& path) { return path + ".tmp"; }

void write_file_atomic(const std::string& path, const std::string& contents) {
  note_output_file(path);
  const std::string tmp = tmp_path_for(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error("cannot create '" + tmp + "': " + errno_text());
  const char* p = contents.data();
  size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string why = errno_text();
      ::close(fd);
      ::unlink(tmp.c_str());
      throw Error("cannot write '" + tmp + "': " + why);
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  // Small files (XDMF index, summary): make the data durable before the rename publishes it.
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const std::string why = errno_text();
    ::unlink(tmp.c_str());
    throw Error("cannot flush '" + tmp + "': " + why);
  }
  commit_atomic(tmp, path);
}

void commit_atomic(const std::string& tmp, const std::string& final_path) {
  if (std::rename(tmp.c_str(), final_path.c_str()) != 0)
    throw Error("cannot rename '" + tmp + "' to '" + final_path + "': " + errno_text());
}

AtomicPath::AtomicPath(std::string final_path)
    : final_(std::move(final_path)), tmp_(tmp_path_for(final_)) {
  note_output_file(final_);
}

AtomicPath::~AtomicPath() {
  if (!committed_) ::unlink(tmp_.c_str());
}

void AtomicPath::commit() {
  commit_atomic(tmp_, final_);
  committed_ = true;
}

}  // namespace ballista
