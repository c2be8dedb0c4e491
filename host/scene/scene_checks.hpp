// mfv run --scene: the conformance checks of the materials a scene uses, and
// only those (issue 7). Each distinct parameter set is integrated once, however
// many materials share it; programs are built with the terms the sets use.
#pragma once

#include "checks/suite.hpp"
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace mfv {

// What the run left out, for one check, against the full catalog at the same
// options (checks, scale).
struct LeftOut {
  std::string check;
  size_t full_combinations = 0, scene_combinations = 0;  // models (D/G/F names, or parameter sets)
  uint64_t full_integrals = 0, scene_integrals = 0;      // reciprocity: batches
  uint64_t full_samples = 0, scene_samples = 0;
  double scene_seconds = 0;  // measured integration time
  double full_seconds = 0;   // measured, with --compare-full; else 0
};

struct SceneRun {
  Scene scene;
  SuiteReport rep;
  // per material (scene.materials order): the groups (rep.groups indices) that check it
  std::vector<std::vector<size_t>> material_groups;
  std::vector<LeftOut> left_out;
  int full_builds = 0, scene_builds = 0;
  double seconds = 0;  // measured: the whole scene run, builds and reference included
  bool full_measured = false;
  double full_seconds = 0;  // measured the same way for the full catalog (compare_full)
};

// compare_full: also run the full catalog with the same options and measure
// it, so the time saved is a measurement (costs a full run).
SceneRun run_scene(Runtime& rt, const Scene& scene, const SuiteOptions& opt, bool compare_full = false);

// Per-material summary lines, the left-out table, time saved (console).
void print_scene_console(const SceneRun& run);
// Adds the scene to results.json ("scene") and report.md, then writes the three files.
void write_scene_outputs(const SceneRun& run, const Runtime& rt, const SuiteOptions& opt, const std::string& dir);
std::string scene_json(const SceneRun& run);  // the "scene" object of results.json, as text

}  // namespace mfv
