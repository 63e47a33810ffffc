// camdyn — output files: history.csv, events.csv, summary.json, cam.csv (docs/interface.md).
//
// Every file is written to "PATH.tmp.<pid>" and renamed onto PATH when complete, so a
// reader never sees a half-written file. Numbers are written with full precision (the
// shortest text that reads back to the same double); JSON writes non-finite numbers as
// null.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {

/// A file written under a temporary name ("PATH.tmp.<pid>") and renamed onto PATH by
/// commit(). Destroyed without commit(), it removes the temporary file and leaves PATH as
/// it was.
class AtomicFile {
 public:
  /// Opens the temporary file. @throws std::runtime_error naming the path and the reason.
  explicit AtomicFile(std::string path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// Append bytes. @throws std::runtime_error on a write error.
  void write(std::string_view text);
  /// The underlying stream (for fprintf-style writers); valid until commit().
  std::FILE* stream() { return f_; }
  /// Flush, close and rename onto the final path. @throws std::runtime_error on an error.
  void commit();

  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return tmp_; }

 private:
  std::string path_, tmp_;
  std::FILE* f_ = nullptr;
  bool committed_ = false;
};

/// Write `content` to `path` atomically. @throws std::runtime_error on an error.
void write_file_atomic(const std::string& path, std::string_view content);

/// Create `dir` (like mkdir -p) and check that files can be created in it.
/// @throws SceneError with file "--out", key "out", value `dir` and the rule "output directory is not writable: REASON".
void ensure_output_dir(const std::string& dir);

/// `dir`/`name` (no separator doubling; "" or "." for dir gives `name`).
std::string join_path(const std::string& dir, const std::string& name);

// ---- number and string formatting ---------------------------------------------------

/// Shortest round-trip decimal text of x ("nan", "inf", "-inf" for non-finite values).
std::string format_double(double x);
/// JSON number text of x, "null" when x is not finite.
std::string json_number(double x);
/// `s` as a JSON string literal, quotes included (RFC 8259 escaping; bytes ≥ 0x80 are
/// copied through, invalid UTF-8 is replaced by U+FFFD).
std::string json_string(std::string_view s);

// ---- history and events ---------------------------------------------------------------

/// history.csv text: header from history_columns() (then `extra_columns`, network scenes:
/// Simulator::extra_columns()), one line per row.
std::string history_csv(const std::vector<HistoryRow>& rows,
                        const std::vector<std::string>& extra_columns = {});
/// events.csv text: header "t,kind,impact_velocity,theta,impulse" (with_contact: then
/// ",contact", the contact's name — network scenes and user followers, has_named_contacts),
/// one line per event. The kind column
/// is ContactEvent::kind when it is not empty, else to_string(ContactEvent::type).
std::string events_csv(const std::vector<ContactEvent>& events, bool with_contact = false);

/// An Observer that keeps every row and event in memory as they arrive, so a run that
/// fails or is interrupted still has what it computed; write() puts them on disk.
class HistoryWriter : public Observer {
 public:
  void on_row(const HistoryRow& row) override;
  void on_event(const ContactEvent& event) override;

  const std::vector<HistoryRow>& rows() const { return rows_; }
  const std::vector<ContactEvent>& events() const { return events_; }
  void clear();
  /// The extra history columns (Simulator::extra_columns()); when they begin with named
  /// contacts' columns (has_named_contacts) events.csv also gets the `contact` column.
  void set_extra_columns(std::vector<std::string> names) { extra_ = std::move(names); }

  /// Write DIR/history.csv and DIR/events.csv atomically. @throws std::runtime_error on an error.
  void write(const std::string& dir) const;

 private:
  std::vector<HistoryRow> rows_;
  std::vector<ContactEvent> events_;
  std::vector<std::string> extra_;
};

/// An Observer that writes DIR/history.csv and DIR/events.csv while the run goes, keeping
/// at most about `chunk_bytes` of text per file in memory (O(1) in the number of rows).
/// The files are byte-identical to HistoryWriter::write(DIR) for the same run and the same
/// extra columns (header from history_columns() then `extra_columns`; events.csv gets the
/// `contact` column when `extra_columns` begin with named contacts' columns,
/// has_named_contacts, as events_csv(…, true)).
///
///   camdyn::Simulator sim(scene);
///   camdyn::StreamingHistoryWriter w("out", sim.extra_columns());
///   camdyn::Summary s = sim.run(&w);
///   w.finish();  // out/history.csv, out/events.csv
///
/// Exact behaviour:
///  - The constructor creates "DIR/history.csv.tmp.<pid>" and "DIR/events.csv.tmp.<pid>"
///    (DIR must exist: see ensure_output_dir) and buffers both headers.
///  - on_row / on_event append to a buffer; a buffer larger than chunk_bytes is written to
///    its temporary file and flushed to the OS (fflush), so after a hard crash (the process
///    killed) the rows up to the last chunk are in the temporary files. A write error
///    throws std::runtime_error (inside Simulator::run: the run ends with Termination::Error).
///  - finish() writes the rest, fsyncs, closes and renames both temporary files onto
///    DIR/history.csv and DIR/events.csv (replacing them); afterwards rows and events are
///    ignored. Calling it again does nothing. Throws std::runtime_error on an error, and then
///    leaves the temporary files as they are (nothing is deleted).
///  - The destructor without finish() does the same as finish() (every row and event
///    delivered so far ends up under the final names: a failed or stopped run keeps its
///    rows) but never throws: an error there is swallowed and leaves the temporary files.
///  - Nothing else is written to DIR; DIR/history.csv and DIR/events.csv are untouched
///    until finish() or the destructor.
///  - Placement::InPlace (the CLI's `camdyn run`): the rows go straight to DIR/history.csv
///    and DIR/events.csv (truncated at construction) instead of temporary files, so a
///    process killed with SIGKILL leaves the rows written so far under the final names;
///    finish() then only writes the rest and fsyncs. Buffered text is also written out
///    when it is older than flush_seconds (1 s), so a slow run loses at most that much.
///    A SIGKILL can cut the last line short: every complete line is a row.
class StreamingHistoryWriter : public Observer {
 public:
  /// Where the rows go while the run goes (see above).
  enum class Placement { TemporaryThenRename, InPlace };
  /// @throws std::runtime_error if a temporary file cannot be created.
  explicit StreamingHistoryWriter(std::string dir, std::vector<std::string> extra_columns = {},
                                  std::size_t chunk_bytes = std::size_t(1) << 16,
                                  Placement placement = Placement::TemporaryThenRename);
  StreamingHistoryWriter(const StreamingHistoryWriter&) = delete;
  StreamingHistoryWriter& operator=(const StreamingHistoryWriter&) = delete;
  ~StreamingHistoryWriter() override;

  void on_row(const HistoryRow& row) override;
  void on_event(const ContactEvent& event) override;

  /// Write the buffered text to the temporary files now (fflush). @throws std::runtime_error on an error.
  void flush();
  /// Complete both files (see above). @throws std::runtime_error on an error.
  void finish();

  bool finished() const { return done_; }
  long rows() const { return rows_; }      ///< rows received so far
  long events() const { return events_; }  ///< events received so far
  const std::string& history_path() const { return hist_.path; }  ///< DIR/history.csv
  const std::string& events_path() const { return ev_.path; }     ///< DIR/events.csv

 private:
  struct File {
    std::string path, tmp, buf;
    std::FILE* f = nullptr;
  };
  void write_out(File& file);
  void close_and_rename(File& file, bool sync);
  void write_out_if_stale();

  File hist_, ev_;
  double last_write_ = 0;  ///< steady-clock seconds of the last write_out
  long since_clock_ = 0;   ///< rows and events since the clock was last read
  bool with_contact_ = false;
  bool done_ = false;
  std::size_t chunk_;
  long rows_ = 0, events_ = 0;
};

// ---- summary.json ---------------------------------------------------------------------

/// The scene as a JSON object mirroring to_toml(): title, then the tables cam, follower,
/// spring, contact, solver, run with every key; enumerations as their strings.
std::string scene_json(const Scene& scene, int indent = 0);
/// summary.json "status" of a run that ended: "finished" (Termination::Finished),
/// "interrupted" (stopped by an observer or the caller: Ctrl-C, SIGTERM, SIGHUP) or
/// "failed" (any other termination).
const char* summary_status(const Summary& summary);
/// summary.json: "status" (`status`, or summary_status(summary) when null), the run's
/// statistics and "options" (the resolved scene).
std::string summary_json(const Summary& summary, const Scene& resolved,
                         const char* status = nullptr);
/// Write DIR/summary.json atomically. @throws std::runtime_error on an error.
void write_summary(const std::string& dir, const Summary& summary, const Scene& resolved);
/// Write DIR/summary.json atomically with "status": "running", "finished": false (the
/// CLI's run writes it before the first step, so a killed run says it did not finish).
/// @throws std::runtime_error on an error.
void write_running_summary(const std::string& dir, const Scene& resolved);

// ---- cam.csv --------------------------------------------------------------------------

/// Header of cam.csv: "theta,X_C,dX_dtheta,d2X_dtheta2,beta,r,rho".
const std::vector<std::string>& cam_columns();
/// cam.csv text: `points` rows at θ = 2π i / points, i = 0 … points−1, from Cam::evaluate.
std::string cam_csv(const Cam& cam, int points);

}  // namespace camdyn
