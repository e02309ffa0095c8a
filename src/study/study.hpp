#pragma once
// fissure study: runs a scene with each integrator configuration of a study file, measures the
// error against the reference and the cost, and writes results.csv, results.md and a
// work–precision plot (docs/studies.md).
#include <string>

namespace fissure {

struct StudyConfig;

struct StudyOutcome {
  int runs = 0;    // sweep points run (the reference not counted)
  int failed = 0;  // of which refused or failed
  bool plotted = false;
  std::string folder;
};

// Runs a study read by load_study into study.output_dir. Throws InputError for an unusable study
// or scene, RunError when the reference run fails.
StudyOutcome run_study(const StudyConfig& study, bool progress);

}  // namespace fissure
