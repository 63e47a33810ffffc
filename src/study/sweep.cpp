// camdyn — parameter sweeps: plan, one point, journal, threaded driver (designer.hpp).
//
// Crash safety: every finished point is appended to DIR/sweep.journal as one write()
// of its lines ("R" row, "Q" Poincaré rows, "E" end mark) followed by fsync(), in
// completion order. sweep.csv and poincare.csv are rebuilt from the journal sorted by
// point index and renamed into place. A killed sweep loses at most the points that were
// running; --resume reads the complete points (an "E" line) and skips them.
// DIR/sweep.meta.json holds a fingerprint (FNV-1a of the resolved scene TOML, the keys
// and their values): --resume refuses another sweep's directory.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include "camdyn/designer.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene_keys.hpp"
#include "results/criteria.hpp"
#include "study/thread_pool.hpp"

namespace camdyn {

namespace {

std::string num(double x) { return format_double(x); }

std::string numeric_keys(const Scene& s) {
  std::string out;
  for_each_scene_entry(s, [&](const SceneEntry& e) {
    if (e.kind != SceneEntry::Kind::Real && e.kind != SceneEntry::Kind::Int) return;
    out += (out.empty() ? "" : ", ") + (e.table.empty() ? e.key : e.table + "." + e.key);
  });
  return out;
}

bool is_int_key(const Scene& s, const std::string& key) {
  if (is_network_key(key)) return resolve_network_key(s, key, "--key", key).kind == SceneEntry::Kind::Int;
  bool r = false;
  for_each_scene_entry(s, [&](const SceneEntry& e) {
    if ((e.table.empty() ? e.key : e.table + "." + e.key) == key) r = e.kind == SceneEntry::Kind::Int;
  });
  return r;
}

std::string csv_quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += "\"\"";
    else if (c == '\n' || c == '\r' || c == '\t') q += ' ';
    else q += c;
  }
  return q + "\"";
}

std::string fnv1a(const std::string& s) {
  unsigned long long h = 1469598103934665603ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char b[32];
  std::snprintf(b, sizeof b, "%016llx", h);
  return b;
}

// Watches one point: stops it when its thread CPU time exceeds the limit or the sweep is
// stopped (the Runner polls `flag` every step; on_progress comes every 256 steps).
struct PointWatch : Observer {
  std::atomic<bool> flag{false};
  const std::atomic<bool>* global = nullptr;
  double c0 = 0, limit = 0;
  bool timed_out = false;
  void on_progress(double, double, long) override {
    if (global && global->load()) flag.store(true);
    if (limit > 0 && thread_cpu_seconds() - c0 > limit) {
      timed_out = true;
      flag.store(true);
    }
  }
};

}  // namespace

const std::vector<std::string>& sweep_result_columns() {
  static const std::vector<std::string> cols{
      "finished", "separations", "impacts", "max_contact_force", "min_contact_force",
      "min_force_theta_deg", "first_separation_theta_deg", "first_impact_theta_deg",
      "max_impact_velocity", "max_impact_theta_deg", "max_gap", "min_gap", "period",
      "period_kind", "t_end", "steps", "rejected_steps", "cpu_seconds", "verdict", "message"};
  return cols;
}

void check_sweep_key(const Scene& scene, const std::string& key) {
  if (key == "cam.speed_rpm") {
    if (scene.rpm_per_rev_s > 0) return;
    throw SceneError("--key", 0, "key", key,
                     "the scene gives its speed in rev/s (cam.speed_rev_s): sweep cam.speed_rev_s, or give the "
                     "scene's speed as cam.speed_rpm with cam.rpm_of (then the sweep speaks that rpm)");
  }
  bool found = false, numeric = false;
  std::string kind;
  if (is_network_key(key)) {  // "elements.valve_spring.preload": the entry by name or index
    NetworkKey k;
    try {
      k = resolve_network_key(scene, key, "--key", key);
    } catch (const SceneError& e) {
      throw SceneError("--key", 0, "key", key, e.rule());
    }
    if (k.kind == SceneEntry::Kind::Real || k.kind == SceneEntry::Kind::Int) return;
    throw SceneError("--key", 0, "key", key,
                     std::string("is ") + (k.kind == SceneEntry::Kind::Str ? "a string" : "an array of node names") +
                         ", not a number: only numeric keys can be swept");
  }
  for_each_scene_entry(scene, [&](const SceneEntry& e) {
    if ((e.table.empty() ? e.key : e.table + "." + e.key) != key) return;
    found = true;
    numeric = e.kind == SceneEntry::Kind::Real || e.kind == SceneEntry::Kind::Int;
    kind = e.kind == SceneEntry::Kind::Str ? "a string" : e.kind == SceneEntry::Kind::Bool ? "a boolean" : "an array";
  });
  if (!found)
    throw SceneError("--key", 0, "key", key, "unknown scene key (numeric keys: " + numeric_keys(scene) + ")");
  if (!numeric)
    throw SceneError("--key", 0, "key", key,
                     "is " + kind + ", not a number: only numeric keys can be swept (" + numeric_keys(scene) + ")");
  // A key the scene does not read gives the same run at every point.
  const std::string unused = unused_key_reason(scene, key);
  if (!unused.empty()) throw SceneError("--key", 0, "key", key, unused + ": every point would be the same run");
}

SweepAxis make_sweep_axis(const Scene& scene, const std::string& key, double from, double to,
                          double step, long points, bool log) {
  check_sweep_key(scene, key);
  if (!std::isfinite(from)) throw SceneError("--from", 0, "from", num(from), "must be a finite number");
  if (!std::isfinite(to)) throw SceneError("--to", 0, "to", num(to), "must be a finite number");
  if (!(from < to))
    throw SceneError("--to", 0, "to", num(to),
                     "must be > --from = " + num(from) + " (empty or reversed range)");
  const bool have_step = !std::isnan(step), have_points = points != 0;
  if (have_step == have_points)
    throw SceneError("--step", 0, "step", have_step ? num(step) : "(none)",
                     "give exactly one of --step S and --points N");
  SweepAxis ax;
  ax.key = key;
  if (have_step) {
    if (log) throw SceneError("--log", 0, "log", "true", "goes with --points N, not --step S");
    if (!(step > 0) || !std::isfinite(step))
      throw SceneError("--step", 0, "step", num(step), "must be > 0");
    const double n = std::floor((to - from) / step * (1 + 1e-12)) + 1;
    if (!(n <= 1e6))
      throw SceneError("--step", 0, "step", num(step),
                       "gives " + num(n) + " points; at most 1000000 points per sweep");
    for (long i = 0; i < static_cast<long>(n); ++i) ax.values.push_back(std::min(to, from + double(i) * step));
  } else {
    if (points < 2) throw SceneError("--points", 0, "points", std::to_string(points), "must be >= 2");
    if (points > 1000000)
      throw SceneError("--points", 0, "points", std::to_string(points), "at most 1000000 points per sweep");
    if (log && !(from > 0))
      throw SceneError("--log", 0, "from", num(from), "--log needs --from > 0 (geometric spacing)");
    for (long i = 0; i < points; ++i) {
      const double x = double(i) / double(points - 1);
      // (A (N−1−i) + B i)/(N−1): decimal bounds give decimal-looking values (14.6, not
      // 14.600000000000001 as A + x (B − A) gives)
      double v = log ? std::exp(std::log(from) + x * (std::log(to) - std::log(from)))
                     : (from * double(points - 1 - i) + to * double(i)) / double(points - 1);
      if (i == 0) v = from;
      if (i == points - 1) v = to;
      ax.values.push_back(v);
    }
  }
  // An integer key takes whole numbers only: a value like 1.5 is refused, not rounded.
  if (is_int_key(scene, key))
    for (std::size_t i = 0; i < ax.values.size(); ++i)
      if (ax.values[i] != std::round(ax.values[i]))
        throw SceneError(have_step ? "--step" : "--points", 0, "key", key,
                         "is an integer key, but the sweep's point " + std::to_string(i) + " is " + num(ax.values[i]) +
                             ": give whole-number --from/--to and --step (or --points that land on whole numbers)");
  return ax;
}

void SweepOptions::validate() const {
  if (axes.empty() || axes.size() > 2)
    throw SceneError("--key", 0, "keys", std::to_string(axes.size()), "a sweep has one key or two (--key2)");
  if (axes.size() == 2 && axes[0].key == axes[1].key)
    throw SceneError("--key2", 0, "key2", axes[1].key, "must differ from --key");
  double total = 1;
  for (const auto& a : axes) {
    if (a.values.empty()) throw SceneError("--key", 0, "key", a.key, "has no values");
    total *= double(a.values.size());
  }
  if (total > 1e6)
    throw SceneError("--points", 0, "points", num(total), "at most 1000000 points per sweep (grid total)");
  if (!(point_timeout_seconds >= 0) || !std::isfinite(point_timeout_seconds))
    throw SceneError("--timeout", 0, "timeout", num(point_timeout_seconds), "must be >= 0 (0: no limit)");
}

std::vector<double> SweepPlan::values(long index) const {
  std::vector<double> v(axes.size());
  long r = index;
  for (std::size_t a = axes.size(); a-- > 0;) {
    const long n = static_cast<long>(axes[a].values.size());
    v[a] = axes[a].values[static_cast<std::size_t>(r % n)];
    r /= n;
  }
  return v;
}

SweepPlan plan_sweep(const Scene& base, const SweepOptions& o) {
  o.validate();
  SweepPlan p;
  p.base = base;
  resolve_defaults(p.base);
  validate(p.base);
  p.axes = o.axes;
  p.total = 1;
  for (const auto& a : p.axes) p.total *= static_cast<long>(a.values.size());
  std::string h, fp = to_toml(p.base);
  for (const auto& a : p.axes) {
    h += a.key + ",";
    fp += "\n#key " + a.key;
    for (double v : a.values) fp += " " + num(v);
  }
  const auto& cols = sweep_result_columns();
  p.criteria = detail::criterion_names(p.base);
  for (std::size_t i = 0; i + 1 < cols.size(); ++i) h += cols[i] + ",";
  for (const std::string& c : p.criteria) h += "criterion_" + c + "_value,criterion_" + c + "_pass,";
  h += cols.back() + "\n";
  p.header = h;
  if (o.follower) {
    // The user follower replaces follower.*, [spring] and the network: those keys would
    // change nothing. Its name enters the fingerprint (a resumed sweep is the same one).
    for (const auto& a : p.axes)
      if (a.key.compare(0, 9, "follower.") == 0 || a.key.compare(0, 7, "spring.") == 0 || is_network_key(a.key))
        throw SceneError("--key", 0, "key", a.key,
                         "is replaced by the user follower (follower.*, [spring] and the network tables are not "
                         "used): sweeping it would change nothing");
    const std::shared_ptr<const FollowerSystem> f = o.follower();
    if (!f) throw SceneError("run_sweep", 0, "follower", "null", "the follower factory returned no follower");
    fp += "\n#follower " + f->name();
    p.follower = o.follower;
  }
  p.fingerprint = fnv1a(fp);
  return p;
}

std::string run_sweep_point(const SweepPlan& plan, long index, bool timing, double timeout,
                            const std::atomic<bool>* stop) {
  const std::vector<double> vals = plan.values(index);
  std::string keys;
  for (double v : vals) keys += num(v) + ",";
  Summary s;
  PointWatch watch;
  watch.global = stop;
  watch.limit = timeout;
  watch.c0 = thread_cpu_seconds();
  try {
    Scene sc = plan.base;
    for (std::size_t a = 0; a < vals.size(); ++a) {
      if (plan.axes[a].key == "cam.speed_rpm")  // the scene's rpm (camshaft or engine) → rev/s
        apply_override(sc, "cam.speed_rev_s=" + num(vals[a] / plan.base.rpm_per_rev_s));
      else
        apply_override(sc, plan.axes[a].key + "=" + num(vals[a]));
    }
    std::unique_ptr<Simulator> sim;
    if (plan.follower) {
      std::shared_ptr<const FollowerSystem> f = plan.follower();
      if (!f) throw SceneError("run_sweep", 0, "follower", "null", "the follower factory returned no follower");
      sim = std::make_unique<Simulator>(sc, std::move(f));
    } else {
      sim = std::make_unique<Simulator>(sc);
    }
    s = sim->run(&watch, &watch.flag);
  } catch (const std::exception& e) {
    s = Summary{};
    s.finished = false;
    s.message = e.what();
  }
  if (stop && stop->load() && !s.finished && !watch.timed_out) return std::string();  // not done
  if (watch.timed_out) {
    const std::string sig = "stopped by caller";  // Simulator::run's default stop reason
    const auto at = s.message.find(sig);
    const std::string why = "timeout: the point took more than " + num(timeout) + " CPU seconds";
    if (at != std::string::npos) s.message.replace(at, sig.size(), why);
    else s.message = why;
  }
  const double cpu = timing ? thread_cpu_seconds() - watch.c0 : 0.0;
  const std::string I = std::to_string(index);
  std::string row = keys;
  auto add = [&](const std::string& f) { row += f + ","; };
  add(s.finished ? "1" : "0");
  add(std::to_string(s.separations));
  add(std::to_string(s.impacts));
  add(num(s.max_contact_force));
  add(num(s.min_contact_force));
  add(num(s.min_force_theta_deg));
  add(num(s.first_separation_theta_deg));
  add(num(s.first_impact_theta_deg));
  add(num(s.max_impact_velocity));
  add(num(s.max_impact_theta_deg));
  add(num(s.max_gap));
  add(num(s.min_gap));
  add(std::to_string(s.period));
  add(s.period_kind);
  add(num(s.t_end));
  add(std::to_string(s.steps));
  add(std::to_string(s.rejected_steps));
  add(num(cpu));
  // the verdict's kinds in order of first occurrence, '+'-joined (docs/contacts.md)
  std::string kinds;
  for (const VerdictItem& v : s.verdict) kinds += (kinds.empty() ? "" : "+") + v.kind;
  add(kinds);
  for (const std::string& name : plan.criteria) {
    const CriterionResult* c = nullptr;
    for (const CriterionResult& x : s.criteria)
      if (x.name == name) c = &x;
    add(c ? num(c->value) : "");
    add(c && !std::isnan(c->value) ? (c->pass ? "1" : "0") : "");
  }
  row += csv_quote(s.message);
  std::string out = "R\t" + I + "\t" + row + "\n";
  for (const auto& p : s.poincare)
    out += "Q\t" + I + "\t" + keys + std::to_string(p.revolution) + "," + num(p.t) + "," + num(p.u_c) + "," +
           num(p.v_c) + "\n";
  out += "E\t" + I + "\n";
  return out;
}

// ---- journal ---------------------------------------------------------------------------

namespace {
std::vector<std::string> split_fields(const std::string& s) {
  std::vector<std::string> out;
  std::size_t b = 0;
  for (;;) {
    const std::size_t c = s.find(',', b);
    out.push_back(s.substr(b, c == std::string::npos ? std::string::npos : c - b));
    if (c == std::string::npos) return out;
    b = c + 1;
  }
}
}  // namespace

SweepJournal::SweepJournal(const SweepPlan& plan, const std::string& dir, bool resume)
    : plan_(plan), dir_(dir) {
  done_.assign(static_cast<std::size_t>(plan.total), 0);
  rows_.assign(static_cast<std::size_t>(plan.total), std::string());
  pc_.assign(static_cast<std::size_t>(plan.total), std::string());
  const std::string jpath = join_path(dir, "sweep.journal"), mpath = join_path(dir, "sweep.meta.json");
  std::string keys;
  for (const auto& a : plan.axes) keys += (keys.empty() ? "" : ", ") + json_string(a.key);
  const std::string meta = "{\n  \"fingerprint\": " + json_string(plan.fingerprint) + ",\n  \"scene\": " +
                           json_string(plan.base.title) + ",\n  \"keys\": [" + keys + "],\n  \"points\": " +
                           std::to_string(plan.total) + "\n}\n";
  std::string clean;
  if (resume) {
    std::ifstream m(mpath);
    std::ifstream j(jpath, std::ios::binary);
    if (m) {
      std::stringstream ss;
      ss << m.rdbuf();
      const std::string text = ss.str();
      if (text.find("\"fingerprint\": " + json_string(plan.fingerprint)) == std::string::npos)
        throw SceneError("--resume", 0, "resume", dir,
                         mpath + " is from another sweep (the scene, the keys or their values differ; "
                                 "this sweep's fingerprint is " + plan.fingerprint +
                             "): use another --out, or run without --resume to start over");
    } else if (j) {
      throw SceneError("--resume", 0, "resume", dir,
                       jpath + " has no " + mpath + ": cannot tell which sweep it belongs to");
    }
    if (j) {
      std::stringstream ss;
      ss << j.rdbuf();
      const std::string text = ss.str();
      // Complete lines only; a point counts when its E line was written.
      // A damaged line (not "R|Q|E<TAB>INDEX<TAB>…" of this plan, or a row with the wrong
      // number of fields) is reported, never used: the journal was edited or corrupted.
      const auto fields = [](const std::string& x) { return std::count(x.begin(), x.end(), ',') + 1; };
      const long row_fields = fields(plan.header.substr(0, plan.header.find('\n')));
      const long pc_fields = long(plan.axes.size()) + 4;  // keys, revolution, t, u_c, v_c
      long lineno = 0;
      auto damaged = [&](const std::string& line, const std::string& why) {
        throw SceneError("--resume", lineno, "sweep.journal", line.substr(0, std::min<std::size_t>(line.size(), 60)),
                         jpath + " line " + std::to_string(lineno) + " is damaged (" + why +
                             "): the journal was edited or corrupted; run without --resume to start over");
      };
      std::map<long, std::string> pending;
      std::size_t pos = 0;
      while (pos < text.size()) {
        const std::size_t nl = text.find('\n', pos);
        if (nl == std::string::npos) break;  // a torn last line (a killed sweep): dropped
        const std::string line = text.substr(pos, nl + 1 - pos);
        pos = nl + 1;
        ++lineno;
        if (line.size() < 4 || line[1] != '\t' || (line[0] != 'R' && line[0] != 'Q' && line[0] != 'E'))
          damaged(line, "not an R, Q or E line");
        const std::size_t t2 = line.find_first_of("\t\n", 2);
        char* end = nullptr;
        const long idx = std::strtol(line.c_str() + 2, &end, 10);
        if (end != line.c_str() + t2 || idx < 0 || idx >= plan.total)
          damaged(line, "no point index in 0 … " + std::to_string(plan.total - 1));
        if (line[0] != 'E') {
          const std::string payload = t2 + 1 < line.size() ? line.substr(t2 + 1, line.size() - t2 - 2) : "";
          // R: the keys, the results, then the message (quoted, may hold commas); Q: numbers.
          const long want = line[0] == 'R' ? row_fields : pc_fields;
          const long have = fields(payload);
          if (line[0] == 'R' ? have < want : have != want)
            damaged(line, std::to_string(have) + " fields, expected " + std::to_string(want));
          const std::vector<std::string> f = split_fields(payload);
          const std::size_t numeric = line[0] == 'R' ? plan.axes.size() + 1 : f.size();  // keys and `finished`
          for (std::size_t k = 0; k < numeric && k < f.size(); ++k) {
            char* e2 = nullptr;
            std::strtod(f[k].c_str(), &e2);
            if (f[k].empty() || *e2 != '\0') damaged(line, "'" + f[k] + "' is not a number");
          }
        }
        if (line[0] == 'E') {
          auto it = pending.find(idx);
          if (it != pending.end() && !done(idx)) take(it->second + line, false), clean += it->second + line;
          pending.erase(idx);
        } else if (line[0] == 'R') {
          pending[idx] = line;
        } else if (line[0] == 'Q') {
          if (pending.count(idx)) pending[idx] += line;
        }
      }
    }
  }
  write_file_atomic(mpath, meta);
  write_file_atomic(jpath, clean);  // the complete points only (no torn line to append to)
  fd_ = ::open(jpath.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(jpath + ": cannot open: " + std::strerror(errno));
}

SweepJournal::~SweepJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void SweepJournal::take(const std::string& block, bool write) {
  long idx = -1;
  std::string row, pc;
  std::size_t pos = 0;
  while (pos < block.size()) {
    std::size_t nl = block.find('\n', pos);
    if (nl == std::string::npos) nl = block.size();
    const std::string line = block.substr(pos, nl - pos);
    pos = nl + 1;
    if (line.size() < 3) continue;
    const std::size_t t2 = line.find('\t', 2);
    idx = std::strtol(line.c_str() + 2, nullptr, 10);
    if (line[0] == 'R') row = line.substr(t2 + 1) + "\n";
    else if (line[0] == 'Q') pc += line.substr(t2 + 1) + "\n";
  }
  if (idx < 0 || idx >= plan_.total || done(idx)) return;
  if (write) {
    std::size_t off = 0;
    while (off < block.size()) {
      const ssize_t w = ::write(fd_, block.data() + off, block.size() - off);
      if (w < 0) {
        if (errno == EINTR) continue;
        throw std::runtime_error("sweep.journal: write failed: " + std::string(std::strerror(errno)));
      }
      off += static_cast<std::size_t>(w);
    }
    ::fsync(fd_);
  }
  const std::size_t i = static_cast<std::size_t>(idx);
  done_[i] = 1;
  rows_[i] = row;
  pc_[i] = pc;
  ++n_done_;
  // finished is the first column after the keys
  std::size_t c = 0, k = 0;
  for (; c < row.size() && k < plan_.axes.size(); ++c)
    if (row[c] == ',') ++k;
  if (c < row.size() && row[c] == '0') ++n_failed_;
}

void SweepJournal::append(const std::string& block) { take(block, true); }

void SweepJournal::write_outputs() const {
  std::string csv = plan_.header, pc;
  for (const auto& a : plan_.axes) pc += a.key + ",";
  pc += "revolution,t,u_c,v_c\n";
  for (long i = 0; i < plan_.total; ++i) {
    csv += rows_[static_cast<std::size_t>(i)];
    pc += pc_[static_cast<std::size_t>(i)];
  }
  write_file_atomic(join_path(dir_, "sweep.csv"), csv);
  write_file_atomic(join_path(dir_, "poincare.csv"), pc);
}

// ---- threaded driver --------------------------------------------------------------------

SweepResult run_sweep(const Scene& base, const SweepOptions& o) {
  const SweepPlan plan = plan_sweep(base, o);
  ensure_output_dir(o.out_dir);
  SweepJournal journal(plan, o.out_dir, o.resume);
  SweepResult res;
  res.total = plan.total;
  res.skipped = journal.done_count();
  std::vector<long> todo;
  for (long i = 0; i < plan.total; ++i)
    if (!journal.done(i)) todo.push_back(i);
  std::mutex mu;
  std::string io_error;
  const auto w0 = std::chrono::steady_clock::now();
  detail::parallel_for(todo.size(), o.jobs, o.stop, [&](std::size_t k) {
    const std::string block = run_sweep_point(plan, todo[k], o.timing, o.point_timeout_seconds, o.stop);
    if (block.empty()) return false;  // stopped
    std::lock_guard<std::mutex> lock(mu);
    try {
      journal.append(block);
      ++res.computed;
    } catch (const std::exception& e) {
      io_error = e.what();
      return false;
    }
    if (o.progress)
      o.progress(journal.done_count(), plan.total, journal.failed_count(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
    return true;
  });
  if (!io_error.empty()) throw std::runtime_error(io_error);
  res.failed = journal.failed_count();
  res.interrupted = journal.done_count() < plan.total;
  journal.write_outputs();
  res.csv_path = join_path(o.out_dir, "sweep.csv");
  res.poincare_path = join_path(o.out_dir, "poincare.csv");
  return res;
}

}  // namespace camdyn
