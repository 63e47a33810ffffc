// camdyn — command-line tool: `camdyn spectrum DIR --column NAME` (order analysis of a
// history column; camdyn/spectrum.hpp) and `camdyn campbell SCENE` (its Campbell diagram over
// a speed range; camdyn/campbell.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/campbell.hpp"
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

int cmd_campbell(const CampbellOpts& o) {
  const Scene scene = required_scene("campbell", o.c);
  if (!(o.points >= 2)) throw SceneError("--points", 0, "points", std::to_string(o.points), "must be >= 2");
  if (!(o.from > 0 && o.to > o.from))
    throw SceneError("--from/--to", 0, "from", fmt_g(o.from) + " .. " + fmt_g(o.to), "needs 0 < A < B [rev/s]");
  CampbellOptions co;
  co.column = o.column;
  for (long i = 0; i < o.points; ++i) co.speeds_rev_s.push_back(o.from + (o.to - o.from) * double(i) / double(o.points - 1));
  co.settle_revolutions = o.settle;
  co.revolutions = o.revolutions;
  co.samples_per_revolution = o.samples;
  co.max_order = o.max_order;
  co.threads = o.jobs;
  co.validate();
  ensure_output_dir(o.out);
  const CampbellDiagram d = campbell(scene, co);
  const double rpm = scene.rpm_per_rev_s;
  std::string csv = std::string("speed_rev_s,") + (rpm > 0 ? "speed_rpm," : "") + "order,amplitude\n";
  for (std::size_t k = 0; k < d.speed_rev_s.size(); ++k)
    for (std::size_t j = 0; j < d.order.size(); ++j)
      csv += format_double(d.speed_rev_s[k]) + "," + (rpm > 0 ? format_double(rpm * d.speed_rev_s[k]) + "," : "") +
             format_double(d.order[j]) + "," + format_double(d.amplitude[k][j]) + "\n";
  write_file_atomic(join_path(o.out, "campbell.csv"), csv);
  std::string lines = "name,frequency_hz\n";
  for (const CampbellLine& l : d.lines) lines += l.name + "," + format_double(l.frequency_hz) + "\n";
  write_file_atomic(join_path(o.out, "campbell_lines.csv"), lines);
  if (!o.quiet) {
    std::printf("campbell: %s at %zu speeds %s .. %s rev/s, %d + %d revolutions each\n", d.column.c_str(),
                d.speed_rev_s.size(), fmt_g(d.speed_rev_s.front()).c_str(), fmt_g(d.speed_rev_s.back()).c_str(),
                o.settle, o.revolutions);
    for (std::size_t k = 0; k < d.speed_rev_s.size(); ++k) {
      std::size_t best = 1;
      for (std::size_t j = 1; j < d.order.size(); ++j)
        if (d.amplitude[k][j] > d.amplitude[k][best]) best = j;
      std::printf("  %s rev/s: largest order %s (amplitude %s)\n", fmt_g(d.speed_rev_s[k]).c_str(),
                  fmt_g(d.order[best]).c_str(), fmt_g(d.amplitude[k][best], 4).c_str());
    }
    for (const CampbellLine& l : d.lines) std::printf("  line %s: %s Hz\n", l.name.c_str(), fmt_g(l.frequency_hz).c_str());
    std::printf("output: %s, %s\n", join_path(o.out, "campbell.csv").c_str(),
                join_path(o.out, "campbell_lines.csv").c_str());
  }
  if (o.plot) {
    std::string why;
    const std::string script = companion_script_path("CAMDYN_CAMPBELL_PLOT_SCRIPT", "camdyn_campbell_plot.py");
    if (script.empty() || run_plot_script({o.out}, &why, script) != 0) {
      std::fprintf(stderr, "camdyn: campbell.png not drawn: %s\n", script.empty() ? "script not found" : why.c_str());
      return kExitFailed;
    }
    if (!o.quiet) std::printf("figure: %s\n", join_path(o.out, "campbell.png").c_str());
  }
  return kExitOk;
}

}  // namespace camdyn_cli
