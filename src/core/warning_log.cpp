#include "core/warning_log.hpp"

#include <memory>
#include <mutex>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

namespace ballista {

namespace {

std::mutex& log_mutex() {
  static std::mutex m;
  return m;
}

std::vector<std::string>& recorded() {
  static std::vector<std::string> w;
  return w;
}

/// Keeps warnings only; the console sinks print as before. A sink sees a message only when the
/// logger's level lets it through, so the logger must not be above warn: -q sets the console
/// sink's level instead (apps/ballista.cpp).
class WarningSink final : public spdlog::sinks::base_sink<spdlog::details::null_mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    if (msg.level != spdlog::level::warn) return;
    const std::lock_guard<std::mutex> lock(log_mutex());
    recorded().emplace_back(msg.payload.data(), msg.payload.size());
  }
  void flush_() override {}
};

}  // namespace

void record_warnings() {
  static const bool installed = [] {
    spdlog::default_logger()->sinks().push_back(std::make_shared<WarningSink>());
    return true;
  }();
  (void)installed;
}

std::size_t warning_count() {
  const std::lock_guard<std::mutex> lock(log_mutex());
  return recorded().size();
}

std::vector<std::string> warnings_since(std::size_t mark) {
  const std::lock_guard<std::mutex> lock(log_mutex());
  const auto& all = recorded();
  return mark < all.size() ? std::vector<std::string>(all.begin() + static_cast<std::ptrdiff_t>(mark), all.end())
                           : std::vector<std::string>{};
}

}  // namespace ballista
