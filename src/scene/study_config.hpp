#pragma once
// A work–precision study file (fissure study STUDY.yaml; docs/studies.md): a scene, a reference,
// and integrator configurations each swept over time steps or tolerances.
#include <string>
#include <vector>

namespace fissure {

// One point of a sweep: the scene with these overrides (key.path=value, as --set).
struct StudyPoint {
  std::string run;        // the configuration's name
  std::string parameter;  // "dt", "rtol" or "" (the reference, or a run without a sweep)
  double value = 0;       // the swept value; 0 for dt: auto (the scene's stable estimate)
  std::vector<std::string> overrides;
};

struct StudyConfig {
  std::string file;
  std::string scene;                   // path of the scene file, resolved against the study's
  std::vector<std::string> scene_set;  // overrides applied to the scene for every run
  double every = 0;                    // compare times every, 2 every, ..., time.end (0: end only)
  std::string output_dir;
  // The reference: a run (reference_run) or a CSV of probe values (reference_probes).
  bool reference_is_run = true;
  StudyPoint reference_run;
  std::string reference_probes;  // CSV path, resolved against the study file
  std::vector<StudyPoint> points;
  // target: the fastest point of each run whose probe error stays within `target_error` of the
  // motion's amplitude, against the baseline run's first point, or the reference run itself
  // when the baseline is "reference" (0: no target).
  double target_error = 0;
  std::string target_baseline;
};

// Reads and checks a study file with `overrides` ("key.path=value", fissure study --set) applied
// to its keys; InputError naming the file, the key and the reason.
StudyConfig load_study(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace fissure
