// camdyn — output files (see output.hpp).
#include "camdyn/output.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>


namespace camdyn {

namespace fs = std::filesystem;

// ---- atomic files -----------------------------------------------------------------------

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  tmp_ = path_ + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  f_ = std::fopen(tmp_.c_str(), "wb");
  if (!f_) {
    throw std::runtime_error("cannot create '" + tmp_ + "': " + std::strerror(errno));
  }
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 16);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    if (f_) std::fclose(f_);
    std::remove(tmp_.c_str());
  }
}

void AtomicFile::write(std::string_view text) {
  if (!f_) throw std::runtime_error("write to '" + path_ + "' after commit");
  if (text.empty()) return;
  if (std::fwrite(text.data(), 1, text.size(), f_) != text.size()) {
    throw std::runtime_error("cannot write '" + tmp_ + "': " + std::strerror(errno));
  }
}

void AtomicFile::commit() {
  if (committed_) return;
  if (!f_) throw std::runtime_error("AtomicFile '" + path_ + "' is not open");
  bool ok = std::fflush(f_) == 0;
  int err = ok ? 0 : errno;
  if (ok && ::fsync(::fileno(f_)) != 0 && errno != EINVAL && errno != EROFS) {
    ok = false;
    err = errno;
  }
  if (std::fclose(f_) != 0 && ok) {
    ok = false;
    err = errno;
  }
  f_ = nullptr;
  if (!ok) {
    std::remove(tmp_.c_str());
    committed_ = true;
    throw std::runtime_error("cannot write '" + tmp_ + "': " + std::strerror(err));
  }
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    err = errno;
    std::remove(tmp_.c_str());
    committed_ = true;
    throw std::runtime_error("cannot rename '" + tmp_ + "' to '" + path_ +
                             "': " + std::strerror(err));
  }
  committed_ = true;
}

void write_file_atomic(const std::string& path, std::string_view content) {
  AtomicFile f(path);
  f.write(content);
  f.commit();
}

std::string join_path(const std::string& dir, const std::string& name) {
  if (dir.empty() || dir == ".") return name;
  if (dir.back() == '/') return dir + name;
  return dir + "/" + name;
}

void ensure_output_dir(const std::string& dir) {
  auto fail = [&](const std::string& reason) {
    throw SceneError("--out", 0, "out", dir, "output directory is not writable: " + reason);
  };
  if (dir.empty()) fail("empty path");
  std::error_code ec;
  const fs::path p(dir);
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) fail("exists and is not a directory");
  } else {
    fs::create_directories(p, ec);
    if (ec) fail(ec.message());
    if (!fs::is_directory(p, ec)) fail("could not be created");
  }
  // access() says yes for root on most file systems: also try to create a file.
  if (::access(dir.c_str(), W_OK | X_OK) != 0) fail(std::strerror(errno));
  const std::string probe =
      join_path(dir, ".camdyn-probe." + std::to_string(static_cast<long>(::getpid())));
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) fail(std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

// ---- formatting ---------------------------------------------------------------------

namespace {

void append_double(std::string& out, double x) {
  if (std::isnan(x)) {
    out += "nan";
    return;
  }
  if (std::isinf(x)) {
    out += x > 0 ? "inf" : "-inf";
    return;
  }
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, x);
  if (res.ec == std::errc()) {
    out.append(buf, res.ptr);
  } else {
    int n = std::snprintf(buf, sizeof buf, "%.17g", x);
    out.append(buf, static_cast<size_t>(n));
  }
}

}  // namespace

std::string format_double(double x) {
  std::string s;
  append_double(s, x);
  return s;
}

// ---- history and events -------------------------------------------------------------

namespace {

void append_row(std::string& out, const HistoryRow& r) {
  const double v[] = {r.t, r.theta, r.u_c, r.v_c, r.a_c, r.contact_force, r.gap};
  for (double x : v) {
    append_double(out, x);
    out += ',';
  }
  out += std::to_string(r.in_contact);
  const double e[] = {r.kinetic, r.potential, r.work_cam, r.dissipated};
  for (double x : e) {
    out += ',';
    append_double(out, x);
  }
  for (double x : r.extra) {
    out += ',';
    append_double(out, x);
  }
  out += '\n';
}

std::string csv_header(const std::vector<std::string>& cols) {
  std::string h;
  for (size_t i = 0; i < cols.size(); ++i) {
    if (i) h += ',';
    h += cols[i];
  }
  h += '\n';
  return h;
}

std::vector<std::string> all_columns(const std::vector<std::string>& extra) {
  std::vector<std::string> c = history_columns();
  c.insert(c.end(), extra.begin(), extra.end());
  return c;
}

void write_history_file(const std::string& path, const std::vector<HistoryRow>& rows,
                        const std::vector<std::string>& extra) {
  AtomicFile f(path);
  f.write(csv_header(all_columns(extra)));
  std::string chunk;
  chunk.reserve(1 << 17);
  for (const auto& r : rows) {
    append_row(chunk, r);
    if (chunk.size() > (1 << 16)) {
      f.write(chunk);
      chunk.clear();
    }
  }
  f.write(chunk);
  f.commit();
}

}  // namespace

std::string history_csv(const std::vector<HistoryRow>& rows, const std::vector<std::string>& extra) {
  std::string out = csv_header(all_columns(extra));
  out.reserve(out.size() + rows.size() * 200);
  for (const auto& r : rows) append_row(out, r);
  return out;
}

namespace {

const char* events_header(bool with_contact) {
  return with_contact ? "t,kind,impact_velocity,theta,impulse,contact\n"
                      : "t,kind,impact_velocity,theta,impulse\n";
}

void append_event(std::string& out, const ContactEvent& e, bool with_contact) {
  append_double(out, e.t);
  out += ',';
  out += to_string(e.type);  // a plain word
  out += ',';
  append_double(out, e.impact_velocity);
  out += ',';
  append_double(out, e.theta);
  out += ',';
  append_double(out, e.impulse);
  if (with_contact) {
    out += ',';
    out += e.contact;  // names are [A-Za-z0-9_-]
  }
  out += '\n';
}

}  // namespace

std::string events_csv(const std::vector<ContactEvent>& events, bool with_contact) {
  std::string out = events_header(with_contact);
  for (const auto& e : events) append_event(out, e, with_contact);
  return out;
}

void HistoryWriter::on_row(const HistoryRow& row) { rows_.push_back(row); }
void HistoryWriter::on_event(const ContactEvent& event) { events_.push_back(event); }
void HistoryWriter::clear() {
  rows_.clear();
  events_.clear();
}

void HistoryWriter::write(const std::string& dir) const {
  write_history_file(join_path(dir, "history.csv"), rows_, extra_);
  write_file_atomic(join_path(dir, "events.csv"), events_csv(events_, has_named_contacts(extra_)));
}

// ---- streaming writer -----------------------------------------------------------------

namespace {
double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
constexpr double kFlushSeconds = 1.0;  // buffered text older than this is written out
constexpr long kClockEvery = 64;       // rows/events between two reads of the clock
}  // namespace

StreamingHistoryWriter::StreamingHistoryWriter(std::string dir, std::vector<std::string> extra,
                                               std::size_t chunk_bytes, Placement placement)
    : with_contact_(has_named_contacts(extra)), chunk_(chunk_bytes) {
  const std::string pid = std::to_string(static_cast<long>(::getpid()));
  hist_.path = join_path(dir, "history.csv");
  ev_.path = join_path(dir, "events.csv");
  last_write_ = steady_seconds();
  for (File* file : {&hist_, &ev_}) {
    file->tmp = placement == Placement::InPlace ? file->path : file->path + ".tmp." + pid;
    file->f = std::fopen(file->tmp.c_str(), "wb");
    if (!file->f) {
      const std::string reason = std::strerror(errno);
      if (hist_.f) {
        std::fclose(hist_.f);
        std::remove(hist_.tmp.c_str());
      }
      throw std::runtime_error("cannot create '" + file->tmp + "': " + reason);
    }
  }
  hist_.buf.reserve(chunk_ + 4096);
  ev_.buf.reserve(std::min<std::size_t>(chunk_, 4096) + 512);
  hist_.buf = csv_header(all_columns(extra));
  ev_.buf = events_header(with_contact_);
}

StreamingHistoryWriter::~StreamingHistoryWriter() {
  if (done_) return;
  done_ = true;
  try {
    close_and_rename(hist_, false);
  } catch (...) {
  }
  try {
    close_and_rename(ev_, false);
  } catch (...) {
  }
}

void StreamingHistoryWriter::write_out(File& file) {
  if (!file.f) throw std::runtime_error("'" + file.tmp + "' is closed");
  if (!file.buf.empty() &&
      std::fwrite(file.buf.data(), 1, file.buf.size(), file.f) != file.buf.size()) {
    throw std::runtime_error("cannot write '" + file.tmp + "': " + std::strerror(errno));
  }
  file.buf.clear();
  if (std::fflush(file.f) != 0) {
    throw std::runtime_error("cannot write '" + file.tmp + "': " + std::strerror(errno));
  }
  last_write_ = steady_seconds();
}

void StreamingHistoryWriter::write_out_if_stale() {
  if (++since_clock_ < kClockEvery) return;
  since_clock_ = 0;
  if (steady_seconds() - last_write_ < kFlushSeconds) return;
  write_out(hist_);
  write_out(ev_);
}

void StreamingHistoryWriter::close_and_rename(File& file, bool sync) {
  if (!file.f) return;
  write_out(file);
  if (sync && ::fsync(::fileno(file.f)) != 0 && errno != EINVAL && errno != EROFS) {
    throw std::runtime_error("cannot write '" + file.tmp + "': " + std::strerror(errno));
  }
  std::FILE* f = file.f;
  file.f = nullptr;
  if (std::fclose(f) != 0) {
    throw std::runtime_error("cannot write '" + file.tmp + "': " + std::strerror(errno));
  }
  if (file.tmp != file.path && std::rename(file.tmp.c_str(), file.path.c_str()) != 0) {
    throw std::runtime_error("cannot rename '" + file.tmp + "' to '" + file.path +
                             "': " + std::strerror(errno));
  }
}

void StreamingHistoryWriter::on_row(const HistoryRow& row) {
  if (done_) return;
  append_row(hist_.buf, row);
  ++rows_;
  if (hist_.buf.size() > chunk_) write_out(hist_);
  write_out_if_stale();
}

void StreamingHistoryWriter::on_event(const ContactEvent& event) {
  if (done_) return;
  append_event(ev_.buf, event, with_contact_);
  ++events_;
  if (ev_.buf.size() > chunk_) write_out(ev_);
  write_out_if_stale();
}

void StreamingHistoryWriter::flush() {
  if (done_) return;
  write_out(hist_);
  write_out(ev_);
}

void StreamingHistoryWriter::finish() {
  if (done_) return;
  done_ = true;
  close_and_rename(hist_, true);
  close_and_rename(ev_, true);
}


// ---- cam.csv --------------------------------------------------------------------------

const std::vector<std::string>& cam_columns() {
  static const std::vector<std::string> cols{"theta", "X_C",  "dX_dtheta", "d2X_dtheta2",
                                             "beta",  "r",    "rho", "d3X_dtheta3",
                                             "pressure_angle", "profile_x", "profile_y"};
  return cols;
}

std::string cam_csv(const Cam& cam, int points) {
  if (points < 1) throw std::invalid_argument("cam_csv: points must be >= 1");
  std::string out = csv_header(cam_columns());
  out.reserve(out.size() + static_cast<size_t>(points) * 140);
  const double two_pi = 2.0 * std::acos(-1.0);
  for (int i = 0; i < points; ++i) {
    const double theta = two_pi * double(i) / double(points);
    const CamPoint p = cam.evaluate(theta);
    double jerk = p.d3X_dtheta3;
    if (std::isnan(jerk)) {  // points spline: no exact h‴; central difference of h″
      const double d = 1e-4;
      jerk = (cam.evaluate(theta + d).d2X_dtheta2 - cam.evaluate(theta - d).d2X_dtheta2) / (2 * d);
    }
    const auto prof = cam.profile_point(theta);
    const double v[] = {theta, p.X_C, p.dX_dtheta, p.d2X_dtheta2, p.beta, p.r, p.rho,
                        jerk, p.pressure_angle, prof[0], prof[1]};
    for (size_t k = 0; k < 11; ++k) {
      if (k) out += ',';
      append_double(out, v[k]);
    }
    out += '\n';
  }
  return out;
}

}  // namespace camdyn