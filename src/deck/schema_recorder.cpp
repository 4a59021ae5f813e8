#include "deck/schema_recorder.hpp"

#include <algorithm>
#include <cctype>

namespace ballista {

namespace {

SchemaRecorder*& active() {
  static SchemaRecorder* recorder = nullptr;
  return recorder;
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

bool same(const SchemaKey& a, const SchemaKey& b) {
  return a.kind == b.kind && a.choices == b.choices && a.range.min == b.range.min && a.range.max == b.range.max &&
         a.range.unit == b.range.unit;
}

}  // namespace

std::string SchemaRecorder::pattern(const std::string& path) const {
  std::string out;
  std::size_t start = 0;
  while (start <= path.size() && !path.empty()) {
    const std::size_t dot = path.find('.', start);
    const std::string seg = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (all_digits(seg))
      out += "[]";
    else if (names_.count(out))
      out += ".*";
    else
      out += (out.empty() ? "" : ".") + seg;
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return out;
}

void SchemaRecorder::key(const std::string& key_path, SchemaKey k) {
  auto& seen = keys_[pattern(key_path)];
  for (SchemaKey& s : seen)
    if (same(s, k)) {
      s.min_items = std::min(s.min_items, k.min_items);  // a vector of 2 in 2D decks, 3 in 3D
      return;
    }
  seen.push_back(std::move(k));
}

void SchemaRecorder::names(const std::string& path) {
  const std::string p = pattern(path);
  names_.insert(p);
  SchemaKey k;
  k.kind = SchemaKey::Kind::Names;
  auto& seen = keys_[p];
  for (SchemaKey& s : seen)
    if (s.kind == SchemaKey::Kind::Object) s.kind = SchemaKey::Kind::Names;  // the map itself, first seen as one
  for (const SchemaKey& s : seen)
    if (s.kind == SchemaKey::Kind::Names) return;
  seen.push_back(k);
}

SchemaRecorder* active_schema_recorder() { return active(); }

SchemaRecording::SchemaRecording(SchemaRecorder& r) : previous_(active()) { active() = &r; }

SchemaRecording::~SchemaRecording() { active() = previous_; }

}  // namespace ballista
