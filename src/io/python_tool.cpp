#include "io/python_tool.hpp"

#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>

#include "core/data_dir.hpp"

#ifndef BALLISTA_PYTHON
#define BALLISTA_PYTHON "/usr/bin/python3"
#endif

namespace ballista {

namespace fs = std::filesystem;

std::string python_interpreter() {
  // The configured interpreter (CMake cache BALLISTA_PYTHON, as the tests use it); the environment
  // variable of the same name overrides it (another Python, or a test of the error path).
  const char* env = std::getenv("BALLISTA_PYTHON");
  return env && *env ? std::string(env) : std::string(BALLISTA_PYTHON);
}

std::string python_tool_path(const std::string& script_name) {
  return (fs::path(data_dir()) / "tools" / script_name).string();
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

namespace {

/// Exit status of a std::system call (-1 if it did not run or was killed).
int run_command(const std::string& cmd) {
  const int rc = std::system(cmd.c_str());
  if (rc == -1) return -1;
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

}  // namespace

std::string run_python_tool(const std::string& script_name, const std::vector<std::string>& args,
                            const std::string& what, const std::string& skip_hint) {
  int status = 0;
  std::string err = run_python_tool_status(script_name, args, status, what, skip_hint);
  if (err.empty() && status != 0) {
    std::string shown = python_interpreter() + " " + python_tool_path(script_name);
    for (const std::string& a : args) shown += " " + a;
    err = fmt::format("{} failed with status {}", shown, status);
  }
  return err;
}

std::string run_python_tool_status(const std::string& script_name, const std::vector<std::string>& args,
                                   int& status, const std::string& what, const std::string& skip_hint) {
  const std::string py = python_interpreter(), script = python_tool_path(script_name);
  const std::string hint = skip_hint.empty() ? "" : ", " + skip_hint;
  const std::string or_hint = skip_hint.empty() ? "" : "; " + skip_hint;
  if (!fs::exists(py))
    return fmt::format(
        "{} needs Python with matplotlib: interpreter {} (BALLISTA_PYTHON) does not exist; "
        "configure with -DBALLISTA_PYTHON=/path/to/python3, set BALLISTA_PYTHON in the "
        "environment{}",
        what, py, hint);
  if (run_command(shell_quote(py) + " -c 'import matplotlib, numpy' >/dev/null 2>&1") != 0)
    return fmt::format(
        "{} needs matplotlib and numpy: {} (BALLISTA_PYTHON) cannot import them (Debian: "
        "apt install python3-matplotlib python3-numpy; or point BALLISTA_PYTHON at another "
        "Python{})",
        what, py, or_hint);
  const std::string noun = what.rfind("the ", 0) == 0 ? what.substr(4) : what;  // "the report" -> "report script"
  if (!fs::exists(script))
    return noun + " script " + script + " not found (looked in the " + data_dir_origin() +
           " data directory; set " + kDataDirEnv + " to the directory holding tools/)";
  std::string cmd = shell_quote(py) + " " + shell_quote(script);
  for (const std::string& a : args) cmd += " " + shell_quote(a);
  status = run_command(cmd);
  return {};
}

}  // namespace ballista
