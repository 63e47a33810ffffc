// camdyn (private) — number formatting for error and run messages (cam, mechanism, contact,
// run).
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace camdyn {

/// Shortest round-trip text of v ("nan", "inf", "-inf" for the non-finite values).
inline std::string fmt_num(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

/// "[a, b, c]"; a list longer than 8 values is shortened to its first 4 and last 2 values
/// and its length ("[a, b, c, d, …, y, z] (180 values)"), so a message stays one line.
inline std::string fmt_list(const std::vector<double>& v) {
  const std::size_t n = v.size();
  const bool cut = n > 8;
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i) {
    if (cut && i == 4) {
      s += ", …";
      i = n - 3;
      continue;
    }
    if (i) s += ", ";
    s += fmt_num(v[i]);
  }
  s += "]";
  if (cut) s += " (" + std::to_string(n) + " values)";
  return s;
}

namespace detail {
/// Six significant digits ("%.6g"): times, gaps and forces in run messages.
inline std::string fmt(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}
}  // namespace detail

}  // namespace camdyn
