#pragma once
// Time-history CSV (e.g. history.csv): a header line of column names, then one line per row,
// every number printed as the shortest text that reads back as the same double (NaN as "nan",
// infinities as "inf"/"-inf"). Each row is flushed to the OS as soon as it is written, so a killed run keeps every
// completed row; only a kill in the middle of a row's write can leave a partial last line.
// The file is appended row by row, not written atomically; it is truncated when opened.
#include <cstdio>
#include <string>
#include <vector>

namespace ballista {

/// A CSV field (RFC 4180): as is, or in double quotes with inner quotes doubled if it contains a
/// separator, quote or line break.
std::string csv_quote(const std::string& s);

class HistoryWriter {
 public:
  /// Creates (truncates) `path` and writes the header; throws Error if it cannot be opened.
  HistoryWriter(std::string path, std::vector<std::string> columns);
  /// Continues the history of a restarted run: `path` must exist with the same header and at
  /// least `resume_bytes` bytes; it is cut to that length (rows written after the checkpoint by
  /// the interrupted run are dropped) and later rows are appended. Throws Error otherwise.
  HistoryWriter(std::string path, std::vector<std::string> columns, long long resume_bytes);
  ~HistoryWriter();
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  /// Appends one row; values.size() must equal the number of columns (throws Error otherwise).
  void row(const std::vector<double>& values);

  /// Bytes of the file so far (header and complete rows): what a checkpoint records.
  long long bytes() const { return bytes_; }
  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
  long long bytes_ = 0;
  std::string header() const;
};

}  // namespace ballista
