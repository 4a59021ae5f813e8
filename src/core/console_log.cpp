#include "core/console_log.hpp"

#include <memory>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace ballista {

namespace {

/// The console sink log_to_stderr installed (null before).
std::shared_ptr<spdlog::sinks::sink>& console_sink() {
  static std::shared_ptr<spdlog::sinks::sink> sink;
  return sink;
}

}  // namespace

void log_to_stderr() {
  auto& sinks = spdlog::default_logger()->sinks();
  // spdlog's default logger has one sink, its colour console on standard output.
  if (!sinks.empty() && !console_sink()) sinks.erase(sinks.begin());
  if (!console_sink()) {
    console_sink() = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
    sinks.insert(sinks.begin(), console_sink());
  }
}

void quiet_console() {
  log_to_stderr();
  console_sink()->set_level(spdlog::level::err);
}

void full_console() {
  log_to_stderr();
  console_sink()->set_level(spdlog::level::trace);
}

}  // namespace ballista
