#include "io/history_writer.hpp"

#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "core/error.hpp"

namespace ballista {

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

namespace {

/// Shortest text that reads back as exactly `v`; "nan", "inf", "-inf" for non-finite values.
void append_number(std::string& line, double v) {
  if (std::isnan(v)) {
    line += "nan";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  line.append(buf, r.ptr);
}
}  // namespace

HistoryWriter::HistoryWriter(std::string path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw Error("history file '" + path_ + "' needs at least one column");
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_) throw Error("cannot create '" + path_ + "': " + std::strerror(errno));
  std::string header;
  for (size_t k = 0; k < columns_.size(); ++k) {
    if (k) header += ',';
    header += csv_quote(columns_[k]);
  }
  header += '\n';
  if (std::fputs(header.c_str(), file_) < 0 || std::fflush(file_) != 0) {
    std::fclose(file_);
    file_ = nullptr;
    throw Error("cannot write '" + path_ + "'");
  }
}

HistoryWriter::~HistoryWriter() {
  if (file_) std::fclose(file_);
}

void HistoryWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_.size())
    throw Error("history row has " + std::to_string(values.size()) + " values, '" + path_ + "' has " +
                std::to_string(columns_.size()) + " columns");
  // Build the whole line first so it reaches the file in one write.
  std::string line;
  for (size_t k = 0; k < values.size(); ++k) {
    if (k) line += ',';
    append_number(line, values[k]);
  }
  line += '\n';
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0)
    throw Error("cannot write '" + path_ + "': " + std::strerror(errno));
}

}  // namespace ballista
