#pragma once
// Running the project's Python tools (tools/*.py: verify report, penetration figures, sweep
// figures) from the C++ commands: one place for the interpreter lookup (BALLISTA_PYTHON), the
// check that it exists and imports numpy and matplotlib, and the quoting of the command line.
#include <string>
#include <vector>

namespace ballista {

/// The interpreter the tools use: the environment variable BALLISTA_PYTHON if set and non-empty
/// (another Python, or a test of the error path), else the CMake cache value of the same name.
std::string python_interpreter();

/// <data_dir()>/tools/<script_name> (core/data_dir.hpp: installed, or the source tree of a build).
std::string python_tool_path(const std::string& script_name);

/// Runs `python tools/<script_name> args...`. Returns an empty string on success, else a message
/// saying what is missing (interpreter, matplotlib/numpy, the script) or how the script failed.
/// `what` names the product in the messages ("the report"), `skip_hint` how to do without it
/// ("or use --no-report"; empty: no hint).
std::string run_python_tool(const std::string& script_name, const std::vector<std::string>& args,
                            const std::string& what = "the plot", const std::string& skip_hint = "");

/// As run_python_tool, for a tool whose exit status is its answer (a report whose checks
/// failed): the status goes to `status` (-1: killed), and only a tool that could not be started
/// (interpreter, numpy/matplotlib, the script missing) gives a message.
std::string run_python_tool_status(const std::string& script_name, const std::vector<std::string>& args,
                                   int& status, const std::string& what = "the plot",
                                   const std::string& skip_hint = "");

/// A single-quoted shell word.
std::string shell_quote(const std::string& s);

}  // namespace ballista
