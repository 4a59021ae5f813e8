#pragma once
// The console side of the log: diagnostics (progress, warnings, errors) on standard error, so that
// standard output carries only what a command reports as its result; -q keeps errors only.
namespace ballista {

/// Sends spdlog's default logger to standard error (colours on a terminal) instead of standard
/// output. Other sinks of the logger (core/warning_log.hpp) are kept.
void log_to_stderr();

/// Errors only on the console (-q). The logger itself keeps its level, so warnings still reach
/// the run's record (summary.json "warnings").
void quiet_console();

/// Every level on the console again (undoes quiet_console; for a process that runs several
/// decks, the Python module).
void full_console();

}  // namespace ballista
