#pragma once
// fissure study: runs a scene with each integrator configuration of a study file, measures the
// error against the reference and the cost, and writes results.csv, results.md and a
// work–precision plot (docs/studies.md).
#include <string>

namespace fissure {

struct StudyOutcome {
  int runs = 0;    // sweep points run (the reference not counted)
  int failed = 0;  // of which refused or failed
  bool plotted = false;
  std::string folder;
};

// Throws InputError for an unusable study or scene, RunError when the reference run fails.
StudyOutcome run_study(const std::string& study_file, bool progress);

}  // namespace fissure
