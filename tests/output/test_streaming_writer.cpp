// StreamingHistoryWriter (issue 17): history.csv / events.csv written as the run goes,
// byte-identical to HistoryWriter::write; ContactEvent::type (EventKind).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "../test_support.hpp"

namespace fs = std::filesystem;
using namespace camdyn;
using camdyn_test::slurp;
using camdyn_test::split;

namespace {

fs::path temp_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() /
               ("camdyn_stream_" + name + "_" + std::to_string(static_cast<long>(::getpid())));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string example(const std::string& file) {
  return std::string(CAMDYN_SOURCE_DIR) + "/examples/" + file;
}

// One run feeding both writers (through on_output, as the run calls them).
struct Tee : Observer {
  std::vector<Observer*> to;
  ObserverAction on_output(const HistoryRow& r) override {
    for (Observer* o : to) o->on_output(r);
    return ObserverAction::Continue;
  }
  void on_event(const ContactEvent& e) override {
    for (Observer* o : to) o->on_event(e);
  }
};

// Runs `scene` once into a HistoryWriter (written to DIR/mem) and a StreamingHistoryWriter
// (DIR/stream, small chunks so that many chunks are written) and compares the files.
Summary expect_identical(const Scene& scene, const std::string& name, long min_events = 0) {
  const fs::path dir = temp_dir(name);
  fs::create_directories(dir / "mem");
  fs::create_directories(dir / "stream");
  Simulator sim(scene);
  HistoryWriter mem;
  mem.set_extra_columns(sim.extra_columns());
  StreamingHistoryWriter stream((dir / "stream").string(), sim.extra_columns(), 1000);
  Tee tee;
  tee.to = {&mem, &stream};
  const Summary s = sim.run(&tee);
  EXPECT_TRUE(s.finished) << s.message;
  // Before finish(): nothing under the final names, the rows so far in the temporary file.
  EXPECT_FALSE(fs::exists(dir / "stream" / "history.csv"));
  const fs::path tmp = dir / "stream" / ("history.csv.tmp." + std::to_string(long(::getpid())));
  EXPECT_TRUE(fs::exists(tmp));
  EXPECT_GT(fs::file_size(tmp), 0u);
  stream.finish();
  EXPECT_FALSE(fs::exists(tmp));
  mem.write((dir / "mem").string());
  EXPECT_EQ(stream.rows(), long(mem.rows().size()));
  EXPECT_EQ(stream.events(), long(mem.events().size()));
  EXPECT_GE(stream.events(), min_events);
  EXPECT_GT(mem.rows().size(), 5u);
  for (const char* f : {"history.csv", "events.csv"}) {
    const std::string a = slurp(dir / "mem" / f), b = slurp(dir / "stream" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == b) << name << ": " << f << " differs (" << a.size() << " vs " << b.size()
                        << " bytes)";
  }
  // And the same as the string writers.
  EXPECT_EQ(slurp(dir / "stream" / "history.csv"), history_csv(mem.rows(), sim.extra_columns()));
  EXPECT_EQ(slurp(dir / "stream" / "events.csv"),
            events_csv(mem.events(), !sim.extra_columns().empty()));
  // Only the two files remain.
  long n = 0;
  for (const auto& e : fs::directory_iterator(dir / "stream")) {
    (void)e;
    ++n;
  }
  EXPECT_EQ(n, 2);
  fs::remove_all(dir);
  return s;
}

}  // namespace

TEST(StreamingWriter, RigidCaseAIdenticalToHistoryWriter) {
  Scene s = paper_case("A");
  apply_override(s, "run.output_dt=1e-3");
  expect_identical(s, "rigid");
}

TEST(StreamingWriter, ElasticB1IdenticalToHistoryWriter) {
  Scene s = load_scene_file(example("case_B1.toml"));
  apply_overrides(s, {"run.t_end=0.01"});
  expect_identical(s, "elastic");
}

TEST(StreamingWriter, NetworkIdenticalToHistoryWriter) {
  Scene s = load_scene_file(example("ohc_bucket_tappet.toml"));
  apply_overrides(s, {"run.t_end=0.012"});
  const Summary sum = expect_identical(s, "network", 1);
  EXPECT_FALSE(sum.events.empty());
}

TEST(StreamingWriter, StoppedRunLeavesValidCsvWithoutFinish) {
  // An observer that stops the run; the writer is destroyed without finish().
  struct StopAt : StreamingHistoryWriter {
    using StreamingHistoryWriter::StreamingHistoryWriter;
    long seen = 0;
    double t_last = -1;
    ObserverAction on_output(const HistoryRow& r) override {
      on_row(r);
      ++seen;
      t_last = r.t;
      return r.t >= 0.02 ? ObserverAction::Stop : ObserverAction::Continue;
    }
  };
  const fs::path dir = temp_dir("stopped");
  Scene s = load_scene_file(example("case_A7.toml"));
  long seen = 0;
  double t_last = -1;
  Summary sum;
  {
    Simulator sim(s);
    auto w = std::make_unique<StopAt>(dir.string(), sim.extra_columns(), 512);
    sum = sim.run(w.get());
    seen = w->seen;
    t_last = w->t_last;
    EXPECT_FALSE(w->finished());
  }  // destroyed without finish(): the rows stay, under the final names
  EXPECT_EQ(sum.termination, Termination::StoppedByObserver);
  const std::string text = slurp(dir / "history.csv");
  ASSERT_FALSE(text.empty());
  ASSERT_EQ(text.back(), '\n');
  std::vector<std::string> lines = split(text.substr(0, text.size() - 1), '\n');
  ASSERT_EQ(long(lines.size()), seen + 1);  // header + every row delivered
  const std::size_t cols = split(lines[0], ',').size();
  EXPECT_EQ(cols, history_columns().size());
  for (const auto& l : lines) ASSERT_EQ(split(l, ',').size(), cols) << l;
  EXPECT_DOUBLE_EQ(std::stod(split(lines.back(), ',')[0]), t_last);
  EXPECT_EQ(slurp(dir / "events.csv"), events_csv(sum.events));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
  fs::remove_all(dir);
}

TEST(StreamingWriter, FinishTwiceAndRowsAfterFinishIgnored) {
  const fs::path dir = temp_dir("twice");
  StreamingHistoryWriter w(dir.string());
  HistoryRow r;
  r.t = 0.5;
  w.on_row(r);
  w.finish();
  w.finish();
  w.on_row(r);
  EXPECT_EQ(w.rows(), 1);
  EXPECT_EQ(slurp(dir / "history.csv"), history_csv({r}));
  EXPECT_EQ(slurp(dir / "events.csv"), events_csv({}));
  fs::remove_all(dir);
}

TEST(StreamingWriter, MissingDirectoryThrows) {
  EXPECT_THROW(StreamingHistoryWriter("/nonexistent/camdyn/dir"), std::runtime_error);
}

TEST(EventKind, NamesAndCsvFallback) {
  EXPECT_STREQ(to_string(EventKind::Impact), "impact");
  EXPECT_STREQ(to_string(EventKind::Separation), "separation");
  EXPECT_STREQ(to_string(EventKind::Tensile), "tensile");
  ContactEvent e;
  e.type = EventKind::Separation;  // kind left empty: events.csv names the type
  EXPECT_EQ(events_csv({e}), "t,kind,impact_velocity,theta,impulse\n0,separation,0,0,0\n");
}

TEST(EventKind, CaseA7ImpactsAndSeparationsTyped) {
  const Scene s = load_scene_file(example("case_A7.toml"));
  Simulator sim(s);
  HistoryWriter w;
  const Summary sum = sim.run(&w);
  ASSERT_TRUE(sum.finished) << sum.message;
  ASSERT_EQ(w.events().size(), sum.events.size());
  long impacts = 0, separations = 0;
  for (std::size_t i = 0; i < sum.events.size(); ++i) {
    const ContactEvent& e = sum.events[i];
    EXPECT_EQ(w.events()[i].type, e.type);
    if (e.type == EventKind::Impact) {
      ++impacts;
      EXPECT_GT(e.impact_velocity, 0.0);
    } else if (e.type == EventKind::Separation) {
      ++separations;
      EXPECT_EQ(e.impact_velocity, 0.0);
    } else {
      ADD_FAILURE() << "unexpected " << to_string(e.type);
    }
  }
  EXPECT_GT(impacts, 0);
  EXPECT_GT(separations, 0);
  EXPECT_EQ(impacts, sum.impacts);
  EXPECT_EQ(separations, sum.separations);
  // summary.json's event_counts come from the types
  const std::string json = summary_json(sum, s);
  EXPECT_NE(json.find("\"impact\": " + std::to_string(impacts)), std::string::npos);
  EXPECT_NE(json.find("\"separation\": " + std::to_string(separations)), std::string::npos);
}

// events.csv's `contact` column: only where the contacts have names (networks, user
// followers), whatever other extra columns a single follower's run writes.
TEST(EventsCsv, ContactColumnOnlyWhereContactsHaveNames) {
  EXPECT_TRUE(has_named_contacts({"F_cam", "gap_cam", "in_cam", "u_valve"}));
  EXPECT_FALSE(has_named_contacts({}));
  EXPECT_FALSE(has_named_contacts({"film_thickness", "lambda"}));
  EXPECT_FALSE(has_named_contacts({"F_cam", "gap_seat", "in_cam"}));

  // A rigid follower with designer, oil-film and friction columns: extra columns, no names.
  Scene rigid = paper_case("A");
  apply_overrides(rigid, {"run.t_end=0.02", "run.designer_columns=true", "cam.width=10",
                          "lubricant.viscosity=1e-8", "cam.friction_coefficient=0.05"});
  Simulator sim(rigid);
  ASSERT_FALSE(sim.extra_columns().empty());
  EXPECT_FALSE(has_named_contacts(sim.extra_columns()));
  const fs::path dir = temp_dir("contact_column");
  HistoryWriter w;
  w.set_extra_columns(sim.extra_columns());
  ASSERT_TRUE(sim.run(&w).finished);
  w.write(dir.string());
  const std::string events = slurp(dir / "events.csv");
  EXPECT_EQ(events.substr(0, events.find('\n')), "t,kind,impact_velocity,theta,impulse");
  fs::remove_all(dir);

  const Simulator net(load_scene_file(example("ohc_bucket_tappet.toml")));
  EXPECT_TRUE(has_named_contacts(net.extra_columns()));
}
