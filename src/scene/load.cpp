// camdyn — loading a scene: parse_scene, load_scene_file (with --set overrides, paths
// relative to the file), resolve_defaults, and the paper's cases (scene/scene.cpp parses).
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <toml++/toml.h>

#include "camdyn/scene.hpp"
#include "scene/detail.hpp"
#include "scene/fields.hpp"

namespace camdyn {

using namespace scene_detail;

// ---------------------------------------------------------------- public functions

void resolve_defaults(Scene& scene) {
  if (scene.contact.tol_u == 0.0) scene.contact.tol_u = paper_tol_u(scene.follower.kind);
}

Scene parse_scene(std::string_view toml_text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw SceneError(source_name, static_cast<int>(e.source().begin.line), "", "", std::string(e.description()));
  }
  return from_table(root, source_name, true);
}

namespace {
std::string read_scene_text(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path, 0, "", "", "cannot read scene file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw SceneError(path, 0, "", "", std::string("cannot read scene file: ") + std::strerror(err ? err : ENOENT));
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw SceneError(path, 0, "", "", std::string("cannot read scene file: ") + std::strerror(errno));
  return ss.str();
}

// cam.lift_table: a relative path is the scene file's neighbour.
void resolve_relative_paths(toml::table& root, const std::string& path) {
  if (auto* cam = root["cam"].as_table())
    if (auto* t = cam->get("lift_table"); t && t->is_string()) {
      const std::filesystem::path p(t->value_or(std::string()));
      if (!p.empty() && p.is_relative())
        cam->insert_or_assign("lift_table", (std::filesystem::path(path).parent_path() / p).lexically_normal().string());
    }
}
}  // namespace

Scene load_scene_file(const std::string& path) { return load_scene_file(path, {}); }

Scene load_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  const std::string text = read_scene_text(path);
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw SceneError(path, static_cast<int>(e.source().begin.line), "", "", std::string(e.description()));
  }
  resolve_relative_paths(root, path);
  return scene_detail::scene_from_table(root, path, overrides);
}

// The loaders check the rules on every scene they return (from_table with check_rules, after
// the overrides): their result is a validated scene as it is.
ValidatedScene load_validated_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return ValidatedScene(load_scene_file(path, overrides));
}

ValidatedScene parse_validated_scene(std::string_view toml_text, const std::string& source_name,
                                     const std::vector<std::string>& overrides) {
  return ValidatedScene(parse_scene(toml_text, source_name, overrides));
}

// ---------------------------------------------------------------- paper cases

Scene paper_case(const std::string& name) {
  Scene s;
  s.cam.profile = CamProfileKind::Points;
  s.cam.angles_deg = {0, 45, 90, 135, 180, 225, 270, 315};
  s.cam.radii = {2.0, 2.0, 2.0, 2.1, 3.0, 2.1, 2.0, 2.0};
  s.cam.theta0_deg = 0.0;
  s.spring.stiffness = 500.0;
  s.spring.precompression = 7.0;
  s.contact.model = ContactModel::Lee;
  s.solver.integrator = Integrator::ArkodeErk;
  s.run.t_end = 1.0;
  s.run.output_dt = 1e-4;
  s.follower.mass = 1.0;
  if (name == "A") {
    s.title = "Case A \u2014 rigid follower, 1.75 rev/s (Lee 1997 \u00a74.1)";
    s.follower.kind = FollowerKind::Rigid;
    s.cam.speed_rev_s = 1.75;
    s.solver.rtol = 1e-7;
    s.contact.tol_u = 1e-8;
  } else if (name == "B1" || name == "B2") {
    const bool b2 = name == "B2";
    s.title = b2 ? "Case B2 \u2014 elastic follower, 5 rev/s (Lee 1997 \u00a74.2)"
                 : "Case B1 \u2014 elastic follower, 1.75 rev/s (Lee 1997 \u00a74.2)";
    s.follower.kind = FollowerKind::ElasticBar;
    s.follower.youngs_modulus = 1e7;
    s.follower.area = 3.0;
    s.follower.length = 24.0;
    s.follower.elements = 40;
    s.follower.mass_matrix = MassMatrixKind::Consistent;
    s.cam.speed_rev_s = b2 ? 5.0 : 1.75;
    s.solver.rtol = 1e-6;
    s.contact.tol_u = 1e-7;
  } else {
    throw SceneError("--case", 0, "case", name, "unknown paper case (allowed: A, B1, B2)");
  }
  return s;
}

Scene default_scene() { return paper_case("B2"); }

}  // namespace camdyn
