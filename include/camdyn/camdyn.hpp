// camdyn — the whole public API in one include:
//
//   #include <camdyn/camdyn.hpp>
//
//   scene.hpp            Scene (the TOML file as a struct), load_scene_file, parse_scene,
//                        validate, to_toml; network.hpp (valve-train networks),
//                        cam_spec.hpp (CamSpec, the [cam] table), scene_error.hpp (SceneError)
//   simulator.hpp        Simulator, simulate() (includes the three below)
//   history.hpp          HistoryRow, ContactEvent, EventKind, history_columns()
//   observer.hpp         Observer (on_output, on_event, on_step, on_progress), StepInfo
//   summary.hpp          Summary (BriefReport, FullReport), Termination and the results
//                        a Summary holds (contacts, elements, verdict, criteria, contract)
//   follower_system.hpp  FollowerSystem: bring your own follower
//   initial_state.hpp    initial_state_on_cam and the cam's lift base
//   cam.hpp, motion_law.hpp, hertz.hpp   the cam's profile, motion laws, Hertz stress
//   designer.hpp         required contact force, jump speed, speed sweeps
//   batch.hpp            run_batch: scenes in parallel
//   output.hpp           history.csv, events.csv, summary.json writers
//   scene_keys.hpp, scene_warnings.hpp, model_description.hpp
//
// Each header can also be included on its own. Nothing here needs Eigen or SUNDIALS.
#pragma once

#include "camdyn/batch.hpp"
#include "camdyn/cam.hpp"
#include "camdyn/cam_spec.hpp"
#include "camdyn/campbell.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/hertz.hpp"
#include "camdyn/history.hpp"
#include "camdyn/initial_state.hpp"
#include "camdyn/lift_table.hpp"
#include "camdyn/model_description.hpp"
#include "camdyn/motion_law.hpp"
#include "camdyn/network.hpp"
#include "camdyn/observer.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/scene_error.hpp"
#include "camdyn/scene_keys.hpp"
#include "camdyn/scene_warnings.hpp"
#include "camdyn/simulator.hpp"
#include "camdyn/spectrum.hpp"
#include "camdyn/summary.hpp"
#include "camdyn/synthesis.hpp"
