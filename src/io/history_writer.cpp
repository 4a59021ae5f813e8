#include "io/history_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/error.hpp"
#include "io/run_folder.hpp"

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

std::string HistoryWriter::header() const {
  std::string h;
  for (size_t k = 0; k < columns_.size(); ++k) {
    if (k) h += ',';
    h += csv_quote(columns_[k]);
  }
  return h + '\n';
}

HistoryWriter::HistoryWriter(std::string path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw Error("history file '" + path_ + "' needs at least one column");
  note_output_file(path_);
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_) throw Error("cannot create '" + path_ + "': " + std::strerror(errno));
  const std::string h = header();
  if (std::fputs(h.c_str(), file_) < 0 || std::fflush(file_) != 0) {
    std::fclose(file_);
    file_ = nullptr;
    throw Error("cannot write '" + path_ + "'");
  }
  bytes_ = static_cast<long long>(h.size());
}

HistoryWriter::HistoryWriter(std::string path, std::vector<std::string> columns, long long resume_bytes)
    : path_(std::move(path)), columns_(std::move(columns)) {
  const std::string h = header();
  std::error_code ec;
  const auto size = std::filesystem::file_size(path_, ec);
  if (ec) throw Error("cannot continue '" + path_ + "': " + ec.message());
  if (resume_bytes < static_cast<long long>(h.size()) || static_cast<long long>(size) < resume_bytes)
    throw Error("cannot continue '" + path_ + "': it holds " + std::to_string(size) + " bytes, the checkpoint needs " +
                std::to_string(resume_bytes));
  std::filesystem::resize_file(path_, static_cast<std::uintmax_t>(resume_bytes), ec);
  if (ec) throw Error("cannot cut '" + path_ + "' back to the checkpoint: " + ec.message());
  file_ = std::fopen(path_.c_str(), "r+");
  if (!file_) throw Error("cannot open '" + path_ + "': " + std::strerror(errno));
  std::string first(h.size(), '\0');
  if (std::fread(first.data(), 1, first.size(), file_) != first.size() || first != h) {
    // Name the difference: the file's first line against this run's columns.
    std::rewind(file_);
    std::string line;
    for (int c; (c = std::fgetc(file_)) != EOF && c != '\n';) line += static_cast<char>(c);
    std::fclose(file_);
    file_ = nullptr;
    std::vector<std::string> theirs;
    std::string cell;
    bool quoted = false;
    for (char c : line + ",") {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) { theirs.push_back(cell); cell.clear(); }
      else cell += c;
    }
    auto missing = [](const std::vector<std::string>& a, const std::vector<std::string>& b) {
      std::string out;
      for (const std::string& x : a)
        if (std::find(b.begin(), b.end(), x) == b.end()) out += (out.empty() ? "" : ", ") + x;
      return out.empty() ? std::string("none") : out;
    };
    throw Error("cannot continue '" + path_ + "': its header differs from this run's columns (this run adds: " +
                missing(columns_, theirs) + "; the file has, and this run does not write: " +
                missing(theirs, columns_) +
                "). Were probes, stages or loads changed by --set at the restart, or was the checkpoint written by "
                "another version of Ballista? Restart it with that version, or run the deck anew.");
  }
  std::fseek(file_, 0, SEEK_END);
  bytes_ = resume_bytes;
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
  bytes_ += static_cast<long long>(line.size());
}

}  // namespace ballista
