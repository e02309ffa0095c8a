// summary.json as an independent JSON reader sees it: every documented key in order, numbers to
// 9 digits, null for non-finite values, and a message with quotes, backslashes, newlines, control
// characters and invalid UTF-8 read back as written (the invalid byte as U+FFFD).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "app/summary_json.hpp"

namespace fissure {
namespace {

TEST(SummaryJson, ReadsBackWithAnyMessageAndNonFiniteNumbers) {
  RunSummary s;
  s.status = "failed";
  s.steps = 12;
  s.dt = 1.0e-5;
  s.max_speed = INFINITY;
  s.energy_drift = 0.123456789123;
  s.message = "cannot write 'out/a\"b\\c'\nreason:\x01 disk \xff full";
  s.energy = {{"kinetic", 1.5}, {"balance", NAN}};
  s.integrator_statistics = {{"factorizations", 3}, {"krylov_iterations", 0}};
  s.model_statistics = {{"deviatoric_exact_rows", 12975}, {"deviatoric_largest_residual", 0.5}};
  const std::string text = summary_json(s);
  const auto j = nlohmann::ordered_json::parse(text);  // throws on invalid JSON or UTF-8
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  const std::vector<std::string> documented = {"status",
                                               "particles",
                                               "ranks",
                                               "bonds",
                                               "steps",
                                               "dt",
                                               "stable_dt",
                                               "wall_seconds",
                                               "seconds_per_step",
                                               "setup_seconds",
                                               "peak_rss_mb",
                                               "energy_drift",
                                               "max_speed",
                                               "broken_bonds",
                                               "fragments",
                                               "post_steps",
                                               "force_evaluations",
                                               "integrator",
                                               "energy",
                                               "message",
                                               "integrator_statistics",
                                               "model_statistics"};
  EXPECT_EQ(keys, documented) << text;
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["steps"], 12);
  EXPECT_EQ(j["dt"].get<double>(), 1.0e-5);
  EXPECT_TRUE(j["max_speed"].is_null());
  EXPECT_EQ(j["energy_drift"].get<double>(), 0.123456789);
  EXPECT_EQ(j["message"], "cannot write 'out/a\"b\\c'\nreason:\x01 disk \xef\xbf\xbd full");
  EXPECT_EQ(j["energy"]["kinetic"].get<double>(), 1.5);
  EXPECT_TRUE(j["energy"]["balance"].is_null());
  EXPECT_TRUE(j["integrator_statistics"]["factorizations"].is_number_integer());
  EXPECT_EQ(j["integrator_statistics"]["factorizations"], 3);
  EXPECT_EQ(j["model_statistics"]["deviatoric_exact_rows"], 12975);
  EXPECT_EQ(j["model_statistics"]["deviatoric_largest_residual"].get<double>(), 0.5);
}

}  // namespace
}  // namespace fissure
