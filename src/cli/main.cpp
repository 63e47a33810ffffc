// camdyn — command-line tool (docs/interface.md "Command line").
//
//   camdyn run   [SCENE.toml] [--out DIR] [--set KEY=VALUE]... [--quiet] [--plot]
//   camdyn cam   [SCENE.toml] [--out DIR] [--points N] [--set KEY=VALUE]...
//   camdyn scene [SCENE.toml] [--resolved] [--set KEY=VALUE]...   camdyn scene --keys [--json]
//   camdyn plot  DIR [--zoom T0 T1]
//   camdyn report DIR
//   camdyn bench [SCENE ...] [--out DIR] [--quick] [--repeats N]
//   camdyn jump  SCENE [--set KEY=VALUE]... [--out DIR] [--simulate] [--rel-tol R]
//   camdyn sweep SCENE --key KEY --from A --to B (--step S | --points N [--log])
//                [--key2 ...] [--jobs N] [--resume] [--out DIR] [--plot] [--quiet]
//
// Exit status: 0 success; 1 the simulation (or a figure) failed; 2 bad input.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "study/bench.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/scene_keys.hpp"
#include "commands.hpp"
#include "sweep_mpi.hpp"

namespace {

using namespace camdyn;
using namespace camdyn_cli;

void add_common(CLI::App* sub, CommonOpts& c, const char* scene_help) {
  sub->add_option("scene", c.scene_file, scene_help)->type_name("SCENE.toml");
  sub->add_option("--case", c.case_name,
                  "Use one of the paper's reference cases instead of a file: A, B1, B2")
      ->type_name("NAME");
  sub->add_option("--set", c.sets,
                  "Override a scene key, e.g. --set cam.speed_rev_s=3 --set "
                  "contact.model=penalty (repeatable; applied in order; value in TOML "
                  "syntax, bare words are strings)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
}

const std::vector<std::string> kCommands{"run", "cam", "scene", "plot", "report", "bench", "jump", "sweep", "spectrum", "campbell"};

int real_main(int argc, char** argv) {
  CLI::App app{
      "camdyn — cam–follower dynamics with impact, separation and elastic deformation "
      "(Lee 1997).",
      "camdyn"};
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 the simulation failed, 2 bad input.\n"
      "Examples:\n"
      "  camdyn run                          # the built-in paper case B2\n"
      "  camdyn run scene.toml --out out --set cam.speed_rev_s=3 --plot\n"
      "  camdyn cam --out out                # cam.csv + cam figures\n"
      "  camdyn scene scene.toml --resolved  # the scene with every default filled in\n"
      "  camdyn bench --quick                # work–precision: Lee vs penalty vs baselines\n"
      "  camdyn jump examples/circle_cam.toml # jump (separation) speed\n"
      "  camdyn sweep examples/case_A7.toml --key cam.speed_rev_s --from 5 --to 8 --points 31\n"
      "  camdyn report out                   # out/report.html: figures and results in words\n"
      "Run 'camdyn COMMAND --help' for the options of a command.");

  RunOpts ro;
  auto* run = app.add_subcommand(
      "run",
      "Simulate a scene (default: the built-in paper case B2, elastic follower at 5 rev/s) "
      "and write DIR/history.csv, DIR/events.csv and DIR/summary.json (also when the run "
      "fails or is interrupted with Ctrl-C)");
  add_common(run, ro.c, "Scene file (TOML); without it the built-in default scene is run");
  run->add_option("-o,--out", ro.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  run->add_flag("-q,--quiet", ro.quiet, "Print nothing but errors");
  run->add_flag("--plot", ro.plot,
                "Draw displacement.png, contact_force.png and contact_force_zoom.png (networks "
                "also network_motion.png, network_forces.png) and the page report.html in DIR "
                "after the run (python3 + matplotlib)");
  run->footer(
      "history.csv columns: " +
      [] {
        std::string h;
        for (const auto& c : history_columns()) h += (h.empty() ? "" : ",") + c;
        return h;
      }() +
      "\nExit status: 0 finished, 1 the simulation failed (message names the time and the "
      "reason), 2 bad input.");

  CamOpts co;
  auto* cam = app.add_subcommand(
      "cam",
      "Cam kinematics over one revolution: DIR/cam.csv (theta,X_C,dX_dtheta,d2X_dtheta2,"
      "beta,r,rho) and the figures cam_profile.png and cam_kinematics.png");
  add_common(cam, co.c, "Scene file (TOML); without it the paper's cam is used");
  cam->add_option("-o,--out", co.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  cam->add_option("-n,--points", co.points, "Number of cam angles θ = 2π i/N, i = 0..N−1")
      ->type_name("N")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000000));
  cam->add_flag("-q,--quiet", co.quiet, "Print nothing but errors");
  cam->add_flag("--no-plot", co.no_plot, "Write cam.csv only, no figures");
  cam->add_flag("--synthesise-from-valve-lift", co.synthesise,
                "The scene's cam.law (or lift table) is the VALVE lift: synthesise the cam through the train "
                "(docs/cam_laws.md \"From the valve lift to the cam\"); writes DIR/cam_lift_table.csv and "
                "DIR/synthesised.toml (run it with `camdyn run`), then the cam's files as usual");
  cam->add_option("--ratio", co.ratio,
                  "Synthesis, translating follower: lever ratio dV/ds > 0 (overrides synthesis.ratio, default 1)");
  cam->add_option("--valve-end-angle", co.valve_end_angle_deg,
                  "Synthesis, oscillating finger: angle ψ₀ [deg] of the pivot–valve-end line from the normal "
                  "to the valve axis at rest (overrides synthesis.valve_end_angle_deg, default 0)");
  cam->add_option("--lash", co.lash,
                  "Synthesis: valve lash [length] ≥ 0, measured at the valve (overrides synthesis.lash, default 0)");
  cam->add_option("--lash-ramp", co.ramp_deg,
                  "Synthesis: cam angle [deg] over which the cam takes up the lash (overrides synthesis.ramp_deg)");

  SceneOpts so;
  auto* scene = app.add_subcommand(
      "scene", "Check a scene and print it as TOML (with --resolved: every default filled in)");
  add_common(scene, so.c, "Scene file (TOML); without it the built-in default scene");
  scene->add_flag("-r,--resolved", so.resolved,
                  "Print the resolved scene (automatic values such as contact.tol_u filled "
                  "in)");
  scene->add_flag("--keys", so.keys,
                  "Print the reference of every scene key (key, type, unit, default, rule, "
                  "description) as Markdown, generated from the scene's key table");
  scene->add_flag("--json", so.json, "With --keys: print the reference as JSON");

  PlotOpts po;
  auto* plot = app.add_subcommand(
      "plot",
      "Draw the figures of an output directory: history.csv → displacement.png, "
      "contact_force.png, contact_force_zoom.png; cam.csv → cam_profile.png, "
      "cam_kinematics.png (python3 + matplotlib)");
  plot->add_option("dir", po.dir, "Output directory of 'camdyn run' or 'camdyn cam'")
      ->type_name("DIR")
      ->required();
  plot->add_option("--zoom", po.zoom,
                   "Time window of contact_force_zoom.png (default: 0.02 s around the "
                   "largest contact force)")
      ->type_name("T0 T1")
      ->expected(2);

  std::string report_dir;
  auto* report = app.add_subcommand(
      "report",
      "One self-contained HTML page of a run or a sweep, DIR/report.html: the figures "
      "(embedded) and the results in words, from summary.json, events.csv and history.csv "
      "(or sweep.csv) (python3 + matplotlib)");
  report->add_option("dir", report_dir, "Output directory of 'camdyn run' or 'camdyn sweep'")
      ->type_name("DIR")
      ->required();

  SpectrumOpts spo;
  auto* spectrum = app.add_subcommand(
      "spectrum",
      "Order analysis of a history column: DIR/history.csv resampled uniformly in cam angle "
      "over whole revolutions, its amplitude per cam order (cycles per camshaft revolution) "
      "→ DIR/spectrum_<column>.csv; prints the largest orders");
  spectrum->add_option("dir", spo.dir, "Output directory of 'camdyn run'")->type_name("DIR")->required();
  spectrum->add_option("--column", spo.column, "History column to analyse")
      ->type_name("NAME")
      ->capture_default_str();
  spectrum->add_option("--revolutions", spo.revolutions, "The last N complete revolutions (0: all)")
      ->type_name("N")
      ->capture_default_str();
  spectrum->add_option("--samples", spo.samples, "Samples per revolution of the resampling")
      ->type_name("N")
      ->capture_default_str();
  spectrum->add_option("--max-order", spo.max_order, "Highest order written")
      ->type_name("K")
      ->capture_default_str();

  CampbellOpts cbo;
  auto* campbell = app.add_subcommand(
      "campbell",
      "Campbell diagram: the scene run at --points camshaft speeds from --from to --to rev/s "
      "(settle, then analysed revolutions each, in parallel), the order spectrum of a history "
      "column at each speed → DIR/campbell.csv (speed_rev_s, order, amplitude), the surge "
      "frequencies of the springs with coil masses → DIR/campbell_lines.csv; --plot draws "
      "DIR/campbell.png (python3 + matplotlib)");
  add_common(campbell, cbo.c, "Scene file (TOML)");
  campbell->add_option("--column", cbo.column, "History column to analyse")->type_name("NAME")->capture_default_str();
  campbell->add_option("--from", cbo.from, "Lowest camshaft speed [rev/s]")->type_name("A")->required();
  campbell->add_option("--to", cbo.to, "Highest camshaft speed [rev/s]")->type_name("B")->required();
  campbell->add_option("--points", cbo.points, "Number of speeds (>= 2)")->type_name("N")->required();
  campbell->add_option("--settle", cbo.settle, "Revolutions run before the analysed ones")->type_name("N")->capture_default_str();
  campbell->add_option("--revolutions", cbo.revolutions, "Revolutions analysed")->type_name("N")->capture_default_str();
  campbell->add_option("--samples", cbo.samples, "Rows per revolution of each run")->type_name("N")->capture_default_str();
  campbell->add_option("--max-order", cbo.max_order, "Highest order written")->type_name("K")->capture_default_str();
  campbell->add_option("-j,--jobs", cbo.jobs, "Worker threads (0: all cores)")->type_name("N")->capture_default_str();
  campbell->add_option("-o,--out", cbo.out, "Output directory (created if missing)")->type_name("DIR")->capture_default_str();
  campbell->add_flag("--plot", cbo.plot, "Draw DIR/campbell.png (python3 + matplotlib)");
  campbell->add_flag("-q,--quiet", cbo.quiet, "No report");

  BenchOpts bo;
  auto* bench = app.add_subcommand(
      "bench",
      "Work–precision benchmark: Lee (engines × tolerances), penalty (linear and "
      "Hunt–Crossley laws × k_p × c_p × rtol on arkode-dirk and cvode-bdf), holonomic and "
      "event runs against an event-driven reference; writes DIR/work_precision.csv, "
      "DIR/work_precision.md (headlines with their goals) and wp_*.png figures");
  bench->add_option("scenes", bo.scenes,
                    "Scene files (TOML) or case names A, A7 (case A at 7 rev/s: separates), "
                    "B1, B2, stiff (E = 5e8 bar on 200 elements), B1_1000 (B1 on 1000 "
                    "elements), ohc, ohv (examples/ohc_bucket_tappet.toml, "
                    "examples/ohv_pushrod_train.toml); default: A A7 B1 B2 stiff B1_1000 "
                    "(--quick: A A7 B1 B2)")
      ->type_name("SCENE");
  bench->add_option("-o,--out", bo.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  bench->add_flag("--quick", bo.quick,
                  "Reduced sweep: Lee at two tolerances, penalty (both laws) at three k_p on "
                  "cvode-bdf, event at two tolerances, elastic bars cut to t_end = 0.01 with "
                  "their reference on arkode-erk (the references are cached: see "
                  "--reference-cache)");
  bench->add_option("--repeats", bo.repeats, "Timing repeats (median CPU time)")
      ->type_name("N")
      ->capture_default_str();
  bench->add_option("--budget", bo.budget,
                    "CPU seconds per run before it is stopped (a Lee series then skips its "
                    "tighter tolerances)")
      ->type_name("SECONDS")
      ->capture_default_str();
  bench->add_option("--t-end", bo.t_end, "Override every scene's run.t_end (0: keep)")
      ->type_name("T");
  bench->add_option("--output-dt", bo.output_dt,
                    "Common output grid every run lands on and is compared on (0: 1e-2 for "
                    "a rigid follower, 1e-3 if it separates, 1e-4 for an elastic one)")
      ->type_name("DT");
  bench->add_option("--reference-cache", bo.reference_cache,
                    "Directory of cached reference runs, keyed by the reference scene and this "
                    "build (default: $XDG_CACHE_HOME/camdyn/bench or ~/.cache/camdyn/bench)")
      ->type_name("DIR");
  bench->add_flag("--no-cache", bo.no_cache, "Run every reference (read and write no cache)");
  bench->add_flag("-q,--quiet", bo.quiet, "Print nothing but errors");
  bench->add_flag("--no-plot", bo.no_plot, "Write the CSV and Markdown only, no figures");
  bench->add_flag("--tolerance-sweep", bo.tolerance_sweep,
                  "Tolerance sweep instead: every contact method x engine over rtol 1e-2..1e-12 "
                  "(tol_u alike) against a tight reference, per scene (names A A7 B1 B2 (0.1 s) "
                  "stiff ohc ohv, or files; default all); writes DIR/tol_sweep.csv, "
                  "tol_sweep_series.csv, tol_sweep.md, tol_sweep_*.png (docs/bench_tolerance_sweep.md)");
  bench->add_option("--rtols", bo.rtols, "Tolerance sweep: the rtol grid (default 1e-2 ... 1e-12, decades)")
      ->delimiter(',')
      ->type_name("R,R,...");
  bench->add_option("--heavy-rtols", bo.heavy_rtols,
                    "Tolerance sweep: the rtol grid of elastic and network scenes (default: --rtols)")
      ->delimiter(',')
      ->type_name("R,R,...");
  bench->add_option("--reference-rtol", bo.reference_rtol,
                    "Tolerance sweep: rtol of the references (atol 1e-2 of it)")
      ->type_name("R")
      ->capture_default_str();
  bench->add_option("--methods", bo.methods, "Tolerance sweep: lee,event,holonomic,penalty (default all)")
      ->delimiter(',')
      ->type_name("M,M,...");
  bench->add_option("--engines", bo.engines,
                    "Tolerance sweep: arkode-erk,arkode-dirk,cvode-bdf,ida (default all)")
      ->delimiter(',')
      ->type_name("E,E,...");

  JumpOpts jo;
  auto* jump = app.add_subcommand(
      "jump",
      "Jump (separation) speed at constant cam speed: closed form for a rigid follower "
      "(min over the cam angle of the required contact force reaches 0); otherwise the "
      "speed-range map: trial speeds on a grid (in parallel, jump.settle_revolutions + "
      "jump.judge_revolutions revolutions each), every boundary where a phenomenon appears or "
      "disappears bisected to --rel-tol; prints every band, writes DIR/jump.json and prints "
      "'jump_speed_rev_s = <lowest separation speed>' as the last line");
  add_common(jump, jo.c, "Scene file (TOML)");
  jump->add_option("-o,--out", jo.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  jump->add_flag("--simulate", jo.simulate, "The speed-range map by simulation also for a rigid follower");
  jump->add_option("--rel-tol", jo.rel_tol, "Simulation: relative width of every boundary's final bracket")
      ->type_name("R")
      ->capture_default_str();
  jump->add_option("--lo", jo.lo, "Simulation: lowest speed of the map [rev/s] (0: automatic)")->type_name("REV_S");
  jump->add_option("--hi", jo.hi, "Simulation: highest speed of the map [rev/s] (0: automatic)")->type_name("REV_S");
  jump->add_option("--points", jo.points, "Simulation: trial speeds of the map's grid")
      ->type_name("N")
      ->capture_default_str();
  jump->add_option("-j,--jobs", jo.jobs, "Simulation: worker threads (0: all cores)")
      ->type_name("N")
      ->capture_default_str();
  jump->add_flag("-q,--quiet", jo.quiet, "Print only the last line");

  SweepOpts swo;
  auto* sweep = app.add_subcommand(
      "sweep",
      "Parameter sweep over one numeric scene key (or a grid of two): one run per point, "
      "in parallel (--jobs, or mpirun -np N camdyn sweep ...); DIR/sweep.csv (one row per "
      "point: the key values, then finished,separations,impacts,max_contact_force,"
      "min_contact_force,... cpu_seconds,message) and DIR/poincare.csv (per-revolution "
      "samples). Finished points are journalled (DIR/sweep.journal, fsync): a killed sweep "
      "loses nothing and --resume skips the points done");
  add_common(sweep, swo.c, "Scene file (TOML)");
  auto add_axis = [&](SweepCliAxis& a, const std::string& sfx) {
    sweep->add_option("--key" + sfx, a.key, "Scene key to sweep, e.g. cam.speed_rev_s")->type_name("KEY");
    sweep->add_option("--from" + sfx, a.from, "First value")->type_name("A");
    sweep->add_option("--to" + sfx, a.to, "Last value (> A)")->type_name("B");
    sweep->add_option("--step" + sfx, a.step, "Spacing (values A, A+S, ... <= B)")->type_name("S");
    sweep->add_option("--points" + sfx, a.points, "Number of values from A to B inclusive (>= 2)")->type_name("N");
    sweep->add_flag("--log" + sfx, a.log, "Geometric spacing with --points (A > 0)");
  };
  add_axis(swo.a1, "");
  add_axis(swo.a2, "2");
  sweep->get_option("--key")->required();
  sweep->add_option("-j,--jobs", swo.jobs, "Worker threads (0: all cores)")->type_name("N")->capture_default_str();
  sweep->add_flag("--resume", swo.resume, "Keep the points already in DIR/sweep.journal (same sweep only)");
  sweep->add_option("-o,--out", swo.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  sweep->add_flag("--no-timing", swo.no_timing, "Write cpu_seconds as 0 (byte-comparable files)");
  sweep->add_option("--timeout", swo.timeout, "CPU seconds per point before it is stopped and recorded as failed (0: none)")
      ->type_name("SECONDS");
  sweep->add_flag("-q,--quiet", swo.quiet, "No progress line or report");
  sweep->add_flag("--plot", swo.plot,
                  "Draw sweep_force.png, sweep_bifurcation.png and sweep_impacts.png and the "
                  "page report.html in DIR (python3 + matplotlib)");
  sweep->footer("Exit status: 0 every point done (failed points are rows with finished = 0), "
                "1 interrupted or I/O error, 2 bad input. Under mpirun rank 0 hands out the "
                "points and computes too; --jobs is ignored there (one thread per rank).");

  // A clear message for a mistyped command (CLI11 would only say "not expected").
  if (argc >= 2 && argv[1][0] != '-') {
    bool known = false;
    for (const auto& c : kCommands) known = known || c == argv[1];
    if (!known) {
      std::fprintf(stderr,
                   "camdyn: unknown command '%s' (allowed: run, cam, scene, plot, report, "
                   "bench, jump, sweep, spectrum, campbell; see camdyn --help)\n",
                   argv[1]);
      return kExitBadInput;
    }
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::string what = e.what();
    if (argc < 2) what = "no command given (allowed: run, cam, scene, plot, report, bench, jump, sweep, spectrum, campbell)";
    std::fprintf(stderr, "camdyn: %s\nRun 'camdyn --help' for the commands and options.\n",
                 what.c_str());
    return kExitBadInput;
  }
  if (po.zoom.size() == 2 && !(po.zoom[0] < po.zoom[1])) {
    throw SceneError("--zoom", 0, "zoom", fmt_g(po.zoom[0]) + " " + fmt_g(po.zoom[1]),
                     "expected T0 < T1");
  }

  if (run->parsed()) return cmd_run(ro);
  if (cam->parsed()) return cmd_cam(co);
  if (scene->parsed()) return cmd_scene(so);
  if (plot->parsed()) return cmd_plot(po);
  if (report->parsed()) return cmd_report(report_dir);
  if (bench->parsed()) return cmd_bench(bo);
  if (jump->parsed()) return cmd_jump(jo);
  if (spectrum->parsed()) return cmd_spectrum(spo);
  if (campbell->parsed()) return cmd_campbell(cbo);
  if (sweep->parsed()) {
    // Under mpirun every rank parses the same command line: report bad input once (rank 0).
    if (camdyn_cli::launched_under_mpi() && camdyn_cli::mpi_rank_from_env() != 0) {
      try {
        return cmd_sweep(swo);
      } catch (const SceneError&) {
        return kExitBadInput;
      }
    }
    return cmd_sweep(swo);
  }
  std::fprintf(stderr, "camdyn: no command given (allowed: run, cam, scene, plot, report, bench, jump, sweep, spectrum, campbell)\n");
  return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return real_main(argc, argv);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "camdyn: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "camdyn: out of memory\n");
    return kExitFailed;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "camdyn: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: %s\n", e.what());
    return kExitFailed;
  } catch (...) {
    std::fprintf(stderr, "camdyn: unknown error\n");
    return kExitFailed;
  }
}
