// camdyn — command-line tool: `camdyn spectrum DIR --column NAME` (order analysis of a
// history column; camdyn/spectrum.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/spectrum.hpp"
#include "commands.hpp"

namespace camdyn_cli {

using namespace camdyn;

namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> f(1);
  for (char c : line) {
    if (c == ',') f.emplace_back();
    else if (c != '\r') f.back() += c;
  }
  return f;
}

}  // namespace

int cmd_spectrum(const SpectrumOpts& o) {
  const std::string path = join_path(o.dir, "history.csv");
  std::ifstream in(path);
  if (!in) throw SceneError("DIR", 0, "dir", o.dir, "holds no history.csv (from 'camdyn run')");
  std::string line;
  if (!std::getline(in, line)) throw SceneError(path, 1, "header", "(empty)", "history.csv has no header line");
  const std::vector<std::string> head = split_csv_line(line);
  auto col = [&](const std::string& name) {
    return int(std::find(head.begin(), head.end(), name) - head.begin());
  };
  const int ct = col("theta"), cy = col(o.column);
  if (ct >= int(head.size())) throw SceneError(path, 1, "theta", "(missing)", "history.csv needs a theta column");
  if (cy >= int(head.size())) {
    std::string all;
    for (const std::string& h : head) all += (all.empty() ? "" : ", ") + h;
    throw SceneError("--column", 0, "column", o.column, "is not a column of " + path + " (columns: " + all + ")");
  }
  std::vector<double> th, y;
  int ln = 1;
  while (std::getline(in, line)) {
    ++ln;
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (int(f.size()) <= std::max(ct, cy)) throw SceneError(path, ln, "row", line.substr(0, 40), "has too few fields");
    char* e1 = nullptr;
    char* e2 = nullptr;
    const double a = std::strtod(f[size_t(ct)].c_str(), &e1), b = std::strtod(f[size_t(cy)].c_str(), &e2);
    if (e1 == f[size_t(ct)].c_str() || e2 == f[size_t(cy)].c_str())
      throw SceneError(path, ln, o.column, f[size_t(cy)], "must be a number");
    if (!th.empty() && a == th.back()) continue;  // a repeated row (an event's two sides)
    th.push_back(a);
    y.push_back(b);
  }
  SpectrumOptions so;
  so.revolutions = o.revolutions;
  so.samples_per_revolution = o.samples;
  so.max_order = o.max_order;
  const OrderSpectrum s = order_spectrum(th, y, so);
  std::string csv = "order,amplitude,phase_deg\n";
  for (std::size_t j = 0; j < s.order.size(); ++j)
    csv += format_double(s.order[j]) + "," + format_double(s.amplitude[j]) + "," + format_double(s.phase_deg[j]) + "\n";
  const std::string out = join_path(o.dir, "spectrum_" + o.column + ".csv");
  write_file_atomic(out, csv);
  std::vector<std::size_t> idx;
  for (std::size_t j = 1; j < s.order.size(); ++j) idx.push_back(j);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return s.amplitude[a] > s.amplitude[b]; });
  std::printf("%s: order spectrum of the last %d revolution(s), %d samples per revolution; mean %s\n",
              o.column.c_str(), s.revolutions, o.samples, fmt_g(s.amplitude[0], 6).c_str());
  std::printf("largest orders (order: amplitude):");
  for (std::size_t i = 0; i < std::min<std::size_t>(8, idx.size()); ++i)
    std::printf(" %s: %s%s", fmt_g(s.order[idx[i]], 6).c_str(), fmt_g(s.amplitude[idx[i]], 4).c_str(),
                i + 1 < std::min<std::size_t>(8, idx.size()) ? "," : "");
  std::printf("\noutput: %s\n", out.c_str());
  return kExitOk;
}

}  // namespace camdyn_cli
