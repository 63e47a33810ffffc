// camdyn (private) — the JSON writer of summary.json: numbers and strings as JSON, a
// pretty-printing object writer, arrays of objects (json_writer.cpp; summary_json.cpp and
// scene_json.cpp write with it).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace camdyn {
namespace detail {

/// x as JSON: the shortest round-trip form, null for NaN and ±inf.
void append_json_number(std::string& out, double x);
/// s as a JSON string: quoted, escaped, invalid UTF-8 replaced by U+FFFD.
void append_json_string(std::string& out, std::string_view s);

// A tiny pretty-printing JSON object writer.
class JsonObject {
 public:
  explicit JsonObject(std::string& out, int indent) : out_(out), indent_(indent) {
    out_ += '{';
  }
  void key(std::string_view k) {
    out_ += first_ ? "\n" : ",\n";
    first_ = false;
    out_.append(static_cast<size_t>(indent_ + 2), ' ');
    append_json_string(out_, k);
    out_ += ": ";
  }
  void num(std::string_view k, double v) {
    key(k);
    append_json_number(out_, v);
  }
  void integer(std::string_view k, long long v) {
    key(k);
    out_ += std::to_string(v);
  }
  void boolean(std::string_view k, bool v) {
    key(k);
    out_ += v ? "true" : "false";
  }
  void str(std::string_view k, std::string_view v) {
    key(k);
    append_json_string(out_, v);
  }
  void nums(std::string_view k, const std::vector<double>& v) {
    key(k);
    out_ += '[';
    for (size_t i = 0; i < v.size(); ++i) {
      if (i) out_ += ", ";
      append_json_number(out_, v[i]);
    }
    out_ += ']';
  }
  void strs(std::string_view k, const std::vector<std::string>& v) {
    key(k);
    out_ += '[';
    for (size_t i = 0; i < v.size(); ++i) {
      if (i) out_ += ", ";
      append_json_string(out_, v[i]);
    }
    out_ += ']';
  }
  void raw(std::string_view k, std::string_view json) {
    key(k);
    out_ += json;
  }
  int child_indent() const { return indent_ + 2; }
  void close() {
    if (!first_) {
      out_ += '\n';
      out_.append(static_cast<size_t>(indent_), ' ');
    }
    out_ += '}';
  }

 private:
  std::string& out_;
  int indent_;
  bool first_ = true;
};

// A JSON array of objects, one per item, each filled by fill(JsonObject&, item), its lines
// indented as the children of `o` ("[]" when empty).
template <class T, class Fill>
std::string object_array(const JsonObject& o, const std::vector<T>& items, Fill fill) {
  std::string t = "[";
  for (size_t i = 0; i < items.size(); ++i) {
    std::string u;
    JsonObject k(u, o.child_indent() + 2);
    fill(k, items[i]);
    k.close();
    t += (i ? ",\n" : "\n") + std::string(size_t(o.child_indent() + 2), ' ') + u;
  }
  t += items.empty() ? "]" : "\n" + std::string(size_t(o.child_indent()), ' ') + "]";
  return t;
}

}  // namespace detail
}  // namespace camdyn
