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
  add_schema_key(keys_[pattern(key_path)], k);
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

void add_schema_key(std::vector<SchemaKey>& kinds, const SchemaKey& k) {
  for (SchemaKey& s : kinds)
    if (s.kind == k.kind && s.choices == k.choices && s.range.min == k.range.min && s.range.max == k.range.max) {
      s.min_items = std::min(s.min_items, k.min_items);  // a vector of 2 in 2D decks, 3 in 3D
      return;
    }
  kinds.push_back(k);
}

SchemaRecorder* active_schema_recorder() { return active(); }

SchemaRecording::SchemaRecording(SchemaRecorder& r) : previous_(active()) { active() = &r; }

SchemaRecording::~SchemaRecording() { active() = previous_; }

}  // namespace ballista
