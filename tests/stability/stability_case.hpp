#pragma once
// One case of the stability suite: a scene run through the fissure executable, its summary and
// energy ledger read back, its figures printed, and the speed no particle can exceed without
// energy appearing from nowhere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <string>

#include "app/run_fissure.hpp"
#include "scene/config.hpp"
#include "scene/scene.hpp"

namespace fissure::test {

struct CaseRun {
  std::string name;
  std::filesystem::path config, out;
  Outcome outcome;
  std::map<std::string, std::string> summary;  // top-level keys, values as written
  std::map<std::string, double> energy;        // summary.json's "energy" object

  double number(const std::string& key) const {
    const auto it = summary.find(key);
    return it == summary.end() ? NAN : std::stod(it->second);
  }
  std::string status() const {
    const auto it = summary.find("status");
    return it == summary.end() ? "" : it->second.substr(1, it->second.size() - 2);
  }
  // An integrator counter from summary.json's "integrator_statistics" object (0 if absent).
  double statistic(const std::string& key) const {
    const std::string text = slurp(out / "summary.json");
    std::smatch m;
    if (!std::regex_search(text, m, std::regex("\"" + key + "\": ([-+0-9.eE]+)"))) return 0.0;
    return std::stod(m[1]);
  }
};

// The numbers of summary.json's "energy" object.
inline std::map<std::string, double> read_energy(const std::filesystem::path& summary) {
  const std::string text = slurp(summary);
  std::map<std::string, double> energy;
  const auto start = text.find("\"energy\": {");
  if (start == std::string::npos) return energy;
  const std::string block = text.substr(start, text.find('}', start) - start);
  static const std::regex pair(R"re("([a-z_]+)": ([-+0-9.eE]+|null))re");
  for (auto it = std::sregex_iterator(block.begin(), block.end(), pair);
       it != std::sregex_iterator(); ++it)
    energy[(*it)[1]] = (*it)[2] == "null" ? NAN : std::stod((*it)[2]);
  return energy;
}

// Writes `yaml` as NAME.yaml in a scratch directory, with `files` (name → content) beside it,
// and runs it with `arguments`.
inline CaseRun run_case(const std::string& name, const std::string& yaml,
                        const std::string& arguments = "",
                        const std::map<std::string, std::string>& files = {}) {
  CaseRun run;
  run.name = name;
  const auto dir = scratch_dir("stability_" + name);
  run.config = dir / (name + ".yaml");
  run.out = dir / "out";
  write_file(run.config, yaml);
  for (const auto& [file, content] : files) write_file(dir / file, content);
  run.outcome =
      run_fissure("run " + run.config.string() + " --out " + run.out.string() + " " + arguments);
  run.summary = read_summary(run.out / "summary.json");
  run.energy = read_energy(run.out / "summary.json");
  return run;
}

// The speed one particle would reach with all the energy the run received, E(0) + the work of
// every load, given to the lightest particle: no stable run can exceed it (Π ≥ 0 and losses ≥ 0
// up to the ledger's balance, which each case bounds separately). It is the one bound every case
// shares, from shattering (where a few light particles do carry most of the energy) to the
// sagging bar (where the energy is spread over every particle and the measured largest speed
// is 26-50x below it); it catches a blow-up, and each case's balance bound, not this one, is
// the tight check on the energy.
// The particle masses come from the case's config file (no case overrides what sets them).
inline double speed_bound(const CaseRun& run) {
  const Scene scene = build_scene(load_config(run.config.string()));
  const double lightest =
      *std::min_element(scene.particles.mass.begin(), scene.particles.mass.end());
  const auto& e = run.energy;
  double received = e.at("initial") + std::max(0.0, e.at("gravity_work")) +
                    std::max(0.0, e.at("constraint_work")) + std::max(0.0, e.at("collider_work"));
  return std::sqrt(2.0 * received / lightest);
}

// One line of figures per case, for the CI log.
inline void report(const CaseRun& run, double speed_limit) {
  std::printf(
      "[stability] %-34s status %-9s steps %6.0f  balance_error %+.3e  max|v| %.4g m/s "
      "(bound %.4g)  broken %.0f  fragments %.0f\n",
      run.name.c_str(), run.status().c_str(), run.number("steps"),
      run.energy.count("balance_error") ? run.energy.at("balance_error") : NAN,
      run.number("max_speed"), speed_limit, run.number("broken_bonds"), run.number("fragments"));
  std::fflush(stdout);
}

// Reports a case that should complete and checks that it did and that no particle outran
// speed_bound(); false (the failure recorded) when it did not complete.
inline bool completed_within_speed_bound(const CaseRun& run) {
  if (run.outcome.exit_code != 0) {
    report(run, NAN);
    ADD_FAILURE() << run.name << " exited with " << run.outcome.exit_code << "\n"
                  << run.outcome.output;
    return false;
  }
  const double bound = speed_bound(run);
  report(run, bound);
  EXPECT_EQ(run.status(), "completed") << run.name;
  EXPECT_LT(run.number("max_speed"), bound) << run.name;
  return true;
}

}  // namespace fissure::test
