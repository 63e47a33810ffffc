// libFuzzer target for the scene loader (issue 7).
//
// Feeds arbitrary bytes to camdyn::parse_scene as a TOML scene file; a scene that parses
// is then turned into a Cam (profile validation: convexity, self-intersection) and a
// CamDrive, and serialised back with to_toml and parsed again (round trip must hold); its
// first line (less a leading '#') is applied as a --set override.
// camdyn::SceneError is the one accepted way to reject input: any other exception,
// crash, sanitizer report, timeout or a failed round trip is a finding.
//
// Built with CAMDYN_FUZZ_RUN (build_and_run.sh does, given the built library as
// CAMDYN_LIB), a scene that loads, and the scene with the --set override applied, are also
// run for a few steps (fuzz_run.hpp: t_end ≤ 2 ms, ≤ 2000 steps, 2 s wall budget, no
// history): no crash, no hang, and no SUNDIALS flag number ("flag -3") in the refusal's
// message, the run's message or its full report.
//
// Build and run: tests/fuzz/build_and_run.sh [SECONDS]
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#ifdef CAMDYN_FUZZ_RUN
#include "fuzz_run.hpp"

static void run_a_few_steps(const camdyn::Scene& scene) {
  const camdyn_fuzz::FewSteps r = camdyn_fuzz::run_few_steps(scene);
  if (camdyn_fuzz::has_flag_number(r.message) || camdyn_fuzz::has_flag_number(r.report)) {
    std::fprintf(stderr, "SUNDIALS flag number in a message:\n%s\n%s\n", r.message.c_str(), r.report.c_str());
    std::abort();
  }
}
#else
static void run_a_few_steps(const camdyn::Scene&) {}
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  camdyn::Scene scene;
  try {
    scene = camdyn::parse_scene(text, "fuzz.toml");
  } catch (const camdyn::SceneError&) {
    return 0;  // rejected with a clear error: fine
  }
  // Accepted: the resolved scene must round-trip through to_toml.
  std::string again = camdyn::to_toml(scene);
  try {
    camdyn::Scene back = camdyn::parse_scene(again, "roundtrip.toml");
    if (!(back == scene)) {
      std::fprintf(stderr, "round trip changed the scene:\n%s\n", again.c_str());
      std::abort();
    }
  } catch (const camdyn::SceneError& e) {
    std::fprintf(stderr, "to_toml output rejected: %s\n%s\n", e.what(), again.c_str());
    std::abort();
  }
  // The input's first line, less a leading '#', as a --set override (network keys by name
  // or index included): applied or rejected with SceneError, nothing else.
  const std::string_view first = text.substr(0, text.find('\n'));
  if (first.find('=') != std::string_view::npos) {
    camdyn::Scene changed = scene;
    try {
      camdyn::apply_override(changed, std::string(first.substr(first.rfind('#', 0) == 0 ? 1 : 0)));
      run_a_few_steps(changed);
    } catch (const camdyn::SceneError&) {
    }
  }
  // The cam must either build or be rejected with SceneError.
  try {
    camdyn::Cam cam(scene.cam);
    (void)cam.evaluate(0.3);
    (void)cam.lift();
    camdyn::CamDrive drive(scene.cam);
    (void)drive.theta(0.5);
  } catch (const camdyn::SceneError&) {
  }
  run_a_few_steps(scene);
  return 0;
}
