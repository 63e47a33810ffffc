// camdyn — command-line tool: `camdyn cam`, `camdyn scene`, `camdyn plot` and `camdyn report`.
#include "commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cerrno>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/lift_table.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/scene_keys.hpp"
#include "camdyn/synthesis.hpp"

namespace camdyn_cli {

using namespace camdyn;
namespace fs = std::filesystem;

int cmd_cam(const CamOpts& o) {
  // Without a scene: the paper cam (default CamSpec) at its default speed.
  Scene sc = build_scene(o.c.scene_file, o.c.case_name, o.c.sets, Scene{}).scene();  // validated once
  ensure_output_dir(o.out);
  if (o.synthesise) {
    if (sc.cam.profile != CamProfileKind::Law && sc.cam.profile != CamProfileKind::Table)
      throw SceneError(o.c.scene_file, 0, "cam.profile", to_string(sc.cam.profile),
                       "--synthesise-from-valve-lift needs the valve lift as cam.profile \"law\" or \"table\"");
    const MotionLaw valve =
        sc.cam.profile == CamProfileKind::Law
            ? MotionLaw::parse(sc.cam.law)
            : [&] {
                const LiftTable t = read_lift_table_csv(sc.cam.lift_table);
                return MotionLaw::from_table(t.angle_deg, t.lift, t.dlift_ddeg, t.d2lift_ddeg2);
              }();
    // the train: the scene's [synthesis], each CLI option given overriding its key (and
    // checked by the same rules, named by the key)
    if (!std::isnan(o.ratio)) sc.synthesis.ratio = o.ratio;
    if (!std::isnan(o.valve_end_angle_deg)) sc.synthesis.valve_end_angle_deg = o.valve_end_angle_deg;
    if (!std::isnan(o.lash)) sc.synthesis.lash = o.lash;
    if (!std::isnan(o.ramp_deg)) sc.synthesis.ramp_deg = o.ramp_deg;
    validate(sc);
    ValveTrainOptions tr;
    tr.ratio = sc.synthesis.ratio;
    tr.valve_end_angle_deg = sc.synthesis.valve_end_angle_deg;
    tr.lash = sc.synthesis.lash;
    tr.ramp_deg = sc.synthesis.ramp_deg;
    tr.points = std::max(o.points, 16);
    const std::string table = join_path(o.out, "cam_lift_table.csv");
    const CamSynthesis syn = synthesise_cam_from_valve_lift(sc.cam, valve, tr, table);
    sc.cam = syn.spec;
    sc.cam.lift_table = "cam_lift_table.csv";  // next to synthesised.toml
    write_file_atomic(join_path(o.out, "synthesised.toml"), to_toml(sc));
    sc.cam.lift_table = table;
    if (!o.quiet)
      std::printf("synthesised the cam from the valve lift: %s (follower lift %s), %s; max pressure angle %s° at "
                  "%s°, smallest radius of curvature %s at %s°\n",
                  table.c_str(), fmt_g(syn.lift).c_str(), join_path(o.out, "synthesised.toml").c_str(),
                  fmt_g(syn.max_pressure_angle_deg).c_str(), fmt_g(syn.max_pressure_angle_at_deg).c_str(),
                  fmt_g(syn.min_radius_of_curvature).c_str(), fmt_g(syn.min_radius_of_curvature_at_deg).c_str());
  }
  Cam cam(sc.cam);  // SceneError on a bad profile → exit 2
  const std::string path = join_path(o.out, "cam.csv");
  try {
    write_file_atomic(path, cam_csv(cam, o.points));
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: cannot write '%s': %s\n", path.c_str(), e.what());
    return kExitFailed;
  }
  // The follower's lift table (docs/cam_laws.md "Lift tables"), for other cam tools.
  const std::string lift_path = join_path(o.out, "lift_table.csv");
  try {
    write_file_atomic(lift_path, lift_table_csv(lift_table_of(cam, std::max(o.points, 4))));
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: cannot write '%s': %s\n", lift_path.c_str(), e.what());
    return kExitFailed;
  }
  double speed = sc.cam.speed_rev_s;
  if (!sc.cam.speed_table_rev_s.empty()) speed = sc.cam.speed_table_rev_s.front();
  // Side file for the figures ('camdyn plot DIR' redraws them at the same speed).
  try {
    write_file_atomic(join_path(o.out, "cam_info.json"),
                      "{\n  \"title\": " + json_string(sc.title) +
                          ",\n  \"speed_rev_s\": " + json_number(speed) +
                          ",\n  \"points\": " + std::to_string(o.points) +
                          ",\n  \"lift\": " + json_number(cam.lift()) +
                          ",\n  \"min_radius_of_curvature\": " +
                          json_number(cam.min_radius_of_curvature()) +
                          ",\n  \"profile\": " + json_string(to_string(sc.cam.profile)) +
                          ",\n  \"follower_face\": " + json_string(to_string(sc.cam.follower_face)) +
                          ",\n  \"follower_offset\": " + json_number(sc.cam.follower_offset) +
                          ",\n  \"roller_radius\": " + json_number(sc.cam.roller_radius) +
                          ",\n  \"follower_motion\": " + json_string(to_string(sc.cam.follower_motion)) +
                          ",\n  \"pivot_x\": " + json_number(sc.cam.pivot_x) +
                          ",\n  \"pivot_y\": " + json_number(sc.cam.pivot_y) +
                          ",\n  \"continuity\": " + json_string(cam.continuity_report()) +
                          "\n}\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: warning: %s\n", e.what());
  }
  if (!o.quiet) {
    std::printf("wrote %s (%d points): lift %s, smallest radius of curvature %s\n",
                path.c_str(), o.points, fmt_g(cam.lift()).c_str(),
                fmt_g(cam.min_radius_of_curvature()).c_str());
    std::printf("wrote %s (angle_deg,lift,dlift_ddeg,d2lift_ddeg2)\n", lift_path.c_str());
    if (!cam.joints().empty())
      std::printf("%s: continuity at the joints: %s\n", cam.law() ? "motion law" : "arcs",
                  cam.continuity_report().c_str());
    if (!cam.breakpoints().empty())
      std::printf("breakpoints: %zu (steps land on them: cam.land_on_breaks = %s)\n", cam.breakpoints().size(),
                  sc.cam.land_on_breaks ? "true" : "false");
    std::fflush(stdout);
  }
  if (!o.no_plot) {
    std::string why;
    // --quiet: the figures are listed below, once.
    std::vector<std::string> args{"cam", o.out, "--speed", fmt_g(speed, 17), "--quiet"};
    const int prc = run_plot_script(args, &why);
    if (prc != 0) {
      std::fprintf(stderr, "camdyn: warning: no cam figures drawn: %s\n", why.c_str());
    } else if (!o.quiet) {
      std::printf("figures: %s, %s, %s\n", join_path(o.out, "cam_profile.png").c_str(),
                  join_path(o.out, "cam_kinematics.png").c_str(),
                  join_path(o.out, "cam_geometry.png").c_str());
    }
  }
  return kExitOk;
}

int cmd_scene(const SceneOpts& o) {
  const bool scene_given = !o.c.scene_file.empty() || !o.c.case_name.empty() || !o.c.sets.empty();
  if (o.keys) {
    // A scene argument next to --keys is still read: a bad one is an error, not ignored.
    if (scene_given) checked_simulator(build_scene(o.c.scene_file, o.c.case_name, o.c.sets, default_scene()));
    if (!write_stdout(o.json ? scene_keys_json() : scene_keys_markdown())) {
      std::fprintf(stderr, "camdyn: scene: cannot write the key reference to stdout: %s\n", std::strerror(errno));
      return kExitFailed;
    }
    return kExitOk;
  }
  if (o.json) throw SceneError("scene", 0, "--json", "", "needs --keys (the scene itself is printed as TOML)");
  // The same checks as `camdyn run` (checked_simulator): what scene accepts, run starts.
  const ValidatedScene sc = build_scene(o.c.scene_file, o.c.case_name, o.c.sets, default_scene());
  checked_simulator(sc);
  if (!write_stdout(to_toml(sc.scene()))) {  // resolved as loaded (--resolved: the same text)
    std::fprintf(stderr, "camdyn: scene: cannot write the scene to stdout: %s\n", std::strerror(errno));
    return kExitFailed;
  }
  return kExitOk;
}

int cmd_plot(const PlotOpts& o) {
  std::error_code ec;
  if (!fs::is_directory(o.dir, ec)) {
    throw SceneError("plot", 0, "DIR", o.dir, "not a directory");
  }
  const bool have_history = fs::is_regular_file(join_path(o.dir, "history.csv"), ec);
  const bool have_cam = fs::is_regular_file(join_path(o.dir, "cam.csv"), ec);
  if (!have_history && !have_cam) {
    throw SceneError("plot", 0, "DIR", o.dir,
                     "holds neither history.csv (from 'camdyn run') nor cam.csv (from "
                     "'camdyn cam')");
  }
  int rc = kExitOk;
  if (have_history) {
    std::vector<std::string> args{"run", o.dir};
    if (o.zoom.size() == 2) {
      args.push_back("--zoom");
      args.push_back(fmt_g(o.zoom[0], 17));
      args.push_back(fmt_g(o.zoom[1], 17));
    }
    std::string why;
    const int prc = run_plot_script(args, &why);
    if (prc == 2) return kExitBadInput;  // the script printed what is wrong with DIR
    if (prc != 0) {
      std::fprintf(stderr, "camdyn: cannot draw the figures: %s\n", why.c_str());
      rc = kExitFailed;
    }
  }
  if (have_cam) {
    std::string why;
    if (run_plot_script({"cam", o.dir}, &why) != 0) {
      std::fprintf(stderr, "camdyn: cannot draw the cam figures: %s\n", why.c_str());
      rc = kExitFailed;
    }
  }
  return rc;
}

int cmd_report(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw SceneError("report", 0, "DIR", dir, "not a directory");
  if (!fs::is_regular_file(join_path(dir, "summary.json"), ec) && !fs::is_regular_file(join_path(dir, "sweep.csv"), ec))
    throw SceneError("report", 0, "DIR", dir,
                     "holds neither summary.json (from 'camdyn run') nor sweep.csv (from 'camdyn sweep')");
  std::string why;
  const int rc = write_report(dir, false, &why);
  if (rc == 2) return kExitBadInput;  // the script printed what is wrong with DIR
  if (rc != 0) {
    std::fprintf(stderr, "camdyn: cannot write the report: %s\n", why.c_str());
    return kExitFailed;
  }
  std::printf("report: %s\n", join_path(dir, "report.html").c_str());
  return kExitOk;
}

}  // namespace camdyn_cli
