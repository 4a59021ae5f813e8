#include "io/summary_writer.hpp"

#include <charconv>
#include <cmath>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace ballista {

namespace {

const char* kind_name(JsonValue::Kind k) {
  switch (k) {
    case JsonValue::Kind::Null: return "null";
    case JsonValue::Kind::Bool: return "bool";
    case JsonValue::Kind::Int: return "integer";
    case JsonValue::Kind::Number: return "number";
    case JsonValue::Kind::String: return "string";
    case JsonValue::Kind::Array: return "array";
    case JsonValue::Kind::Object: return "object";
  }
  return "?";
}

[[noreturn]] void kind_error(JsonValue::Kind have, const char* want) {
  throw Error(std::string("JSON value is ") + kind_name(have) + ", not " + want);
}

/// Length of the valid UTF-8 sequence starting at s[i], or 0 if it is invalid.
size_t utf8_length(const std::string& s, size_t i) {
  const auto b = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = b(i);
  size_t len;
  unsigned min;
  unsigned cp;
  if (c >= 0xC2 && c <= 0xDF) { len = 2; cp = c & 0x1F; min = 0x80; }
  else if (c >= 0xE0 && c <= 0xEF) { len = 3; cp = c & 0x0F; min = 0x800; }
  else if (c >= 0xF0 && c <= 0xF4) { len = 4; cp = c & 0x07; min = 0x10000; }
  else return 0;
  if (i + len > s.size()) return 0;
  for (size_t k = 1; k < len; ++k) {
    if ((b(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (b(i + k) & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return len;
}

void newline(std::string& out, int indent, int level) {
  if (indent < 0) return;
  out += '\n';
  out.append(static_cast<size_t>(indent * level), ' ');
}

}  // namespace

void json_escape_to(std::string& out, const std::string& s) {
  out += '"';
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\b': out += "\\b"; break;
        case '\f': out += "\\f"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default:
          if (c < 0x20) {
            char buf[8];
            static const char hex[] = "0123456789abcdef";
            buf[0] = '\\'; buf[1] = 'u'; buf[2] = '0'; buf[3] = '0';
            buf[4] = hex[c >> 4]; buf[5] = hex[c & 15];
            out.append(buf, 6);
          } else {
            out += static_cast<char>(c);
          }
      }
      ++i;
    } else if (const size_t len = utf8_length(s, i)) {
      out.append(s, i, len);
      i += len;
    } else {
      out += "\\ufffd";  // invalid UTF-8 byte
      ++i;
    }
  }
  out += '"';
}

std::vector<std::string> non_finite_numbers(const JsonValue& v, const std::string& prefix) {
  std::vector<std::string> out;
  const auto join = [&](const std::string& key) { return prefix.empty() ? key : prefix + "." + key; };
  if (v.kind() == JsonValue::Kind::Number && !std::isfinite(v.as_number())) {
    out.push_back(prefix + " = " + (std::isnan(v.as_number()) ? "nan" : v.as_number() > 0 ? "inf" : "-inf"));
  } else if (v.kind() == JsonValue::Kind::Object) {
    for (const std::string& k : v.keys())
      for (auto& s : non_finite_numbers(v.at(k), join(k))) out.push_back(std::move(s));
  } else if (v.kind() == JsonValue::Kind::Array) {
    for (std::size_t i = 0; i < v.size(); ++i)
      for (auto& s : non_finite_numbers(v.at(i), join(std::to_string(i)))) out.push_back(std::move(s));
  }
  return out;
}

JsonValue& JsonValue::operator[](const std::string& key) {
  if (kind_ == Kind::Null) kind_ = Kind::Object;
  if (kind_ != Kind::Object) kind_error(kind_, "object");
  for (size_t k = 0; k < keys_.size(); ++k)
    if (keys_[k] == key) return items_[k];
  keys_.push_back(key);
  items_.emplace_back();
  return items_.back();
}

const JsonValue& JsonValue::at(const std::string& key) const {
  if (kind_ != Kind::Object) kind_error(kind_, "object");
  for (size_t k = 0; k < keys_.size(); ++k)
    if (keys_[k] == key) return items_[k];
  throw Error("JSON object has no member '" + key + "'");
}

bool JsonValue::contains(const std::string& key) const {
  if (kind_ != Kind::Object) return false;
  for (const std::string& k : keys_)
    if (k == key) return true;
  return false;
}

JsonValue& JsonValue::push_back(JsonValue v) {
  if (kind_ == Kind::Null) kind_ = Kind::Array;
  if (kind_ != Kind::Array) kind_error(kind_, "array");
  items_.push_back(std::move(v));
  return items_.back();
}

const JsonValue& JsonValue::at(std::size_t i) const {
  if (kind_ != Kind::Array) kind_error(kind_, "array");
  if (i >= items_.size())
    throw Error("JSON array index " + std::to_string(i) + " out of range (size " +
                std::to_string(items_.size()) + ")");
  return items_[i];
}

bool JsonValue::as_bool() const {
  if (kind_ != Kind::Bool) kind_error(kind_, "bool");
  return bool_;
}
std::int64_t JsonValue::as_int() const {
  if (kind_ != Kind::Int) kind_error(kind_, "integer");
  return int_;
}
double JsonValue::as_number() const {
  if (kind_ == Kind::Int) return static_cast<double>(int_);
  if (kind_ != Kind::Number) kind_error(kind_, "number");
  return number_;
}
const std::string& JsonValue::as_string() const {
  if (kind_ != Kind::String) kind_error(kind_, "string");
  return string_;
}

std::string JsonValue::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  return out;
}

void JsonValue::dump_to(std::string& out, int indent, int level) const {
  switch (kind_) {
    case Kind::Null: out += "null"; return;
    case Kind::Bool: out += bool_ ? "true" : "false"; return;
    case Kind::Int: out += std::to_string(int_); return;
    case Kind::Number: {
      if (!std::isfinite(number_)) {
        out += "null";  // JSON has no NaN or infinity
        return;
      }
      char buf[32];
      const auto r = std::to_chars(buf, buf + sizeof buf, number_);  // shortest exact form
      out.append(buf, r.ptr);
      return;
    }
    case Kind::String: json_escape_to(out, string_); return;
    case Kind::Array: {
      if (items_.empty()) {
        out += "[]";
        return;
      }
      bool flat = true;  // arrays of scalars stay on one line
      for (const JsonValue& v : items_) flat = flat && v.kind_ != Kind::Array && v.kind_ != Kind::Object;
      out += '[';
      for (size_t k = 0; k < items_.size(); ++k) {
        if (k) out += flat && indent >= 0 ? ", " : ",";
        if (!flat) newline(out, indent, level + 1);
        items_[k].dump_to(out, indent, level + 1);
      }
      if (!flat) newline(out, indent, level);
      out += ']';
      return;
    }
    case Kind::Object: {
      if (items_.empty()) {
        out += "{}";
        return;
      }
      out += '{';
      for (size_t k = 0; k < items_.size(); ++k) {
        if (k) out += ',';
        newline(out, indent, level + 1);
        json_escape_to(out, keys_[k]);
        out += indent >= 0 ? ": " : ":";
        items_[k].dump_to(out, indent, level + 1);
      }
      newline(out, indent, level);
      out += '}';
      return;
    }
  }
}

void SummaryWriter::write(const std::string& path) const { write_file_atomic(path, root_.dump(2) + "\n"); }

}  // namespace ballista
