#pragma once
// Error types. Each carries enough context for the user to find the cause without a debugger.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace ballista {

/// `text` cut to at most `limit` characters, the cut marked with the full length, so that a
/// huge bad value (a 200 kB scalar) is not echoed whole in an error message.
inline std::string shorten(const std::string& text, std::size_t limit = 80) {
  if (text.size() <= limit) return text;
  return text.substr(0, limit) + "... (" + std::to_string(text.size()) + " characters)";
}

/// Base of every error Ballista reports to the user.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input deck: names the file, line, column and key path (line/column 1-based, 0 = unknown).
class DeckError : public Error {
 public:
  DeckError(std::string file, int line, int column, std::string key_path, std::string message)
      : Error(format(file, line, column, key_path, message)),
        file_(std::move(file)), line_(line), column_(column), key_path_(std::move(key_path)) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& key_path() const { return key_path_; }

 private:
  static std::string format(const std::string& file, int line, int column, const std::string& key,
                            const std::string& message) {
    std::string where = file.empty() ? std::string("<deck>") : shorten(file, 300);
    if (line > 0) where += ":" + std::to_string(line) + ":" + std::to_string(column);
    // Keys and messages may echo deck text: bounded (values are shortened where they are quoted;
    // this is the backstop).
    return where + ": " + (key.empty() ? std::string() : "'" + shorten(key, 200) + "': ") + shorten(message, 2000);
  }
  std::string file_;
  int line_;
  int column_;
  std::string key_path_;
};

/// An error every MPI rank raised together, with the same message: rank 0 alone reports it.
class CollectiveError : public Error {
 public:
  using Error::Error;
};

/// A run that cannot continue (NaN, inverted particle, energy blow-up, particle left the grid).
class PhysicsError : public Error {
 public:
  using Error::Error;
};

/// A PhysicsError about one point (particle, peridynamic point, material point); carries its
/// global id so that the run can be repeated with that point tracked (`ballista run
/// --track-failed`, output.track.ids).
class ParticleError : public PhysicsError {
 public:
  ParticleError(std::int64_t id, const std::string& message) : PhysicsError(message), id_(id) {}
  std::int64_t id() const { return id_; }

 private:
  std::int64_t id_;
};

}  // namespace ballista
