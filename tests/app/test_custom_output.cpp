// The "add an output" recipe (docs/architecture.md): a test-only output, speed.csv with the
// largest particle speed every output.speed_every, registered from this file alone with its own
// key. A block falling freely under gravity with symplectic Euler has v_n = g h n on every
// particle, so the row at t reads g t: a row at another time, a missing row, or an output that
// never ran gives other numbers. Its key is checked by its own parser, with the key path.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>

#include "app/output_registry.hpp"
#include "app/output_schedule.hpp"
#include "app/run_fissure.hpp"
#include "support/error_message.hpp"
#include "support/free_block.hpp"

namespace fissure {
namespace {

struct SpeedLogOptions final : OutputOptions {
  double every = 0;  // 0: no speed.csv
};

class SpeedLog final : public Observer {
 public:
  explicit SpeedLog(double every) : every_(every), schedule_(every, 0.0) {}
  std::string name() const override { return "speed"; }
  void start(const RunParts& run) override {
    if (every_ > 0) std::ofstream(run.config.output.dir + "/speed.csv") << "time,max_speed\n";
  }
  void after_step(const RunParts& run, const Step&) override {
    if (every_ == 0 || !schedule_.due(run.state.time, run.tolerance())) return;
    double fastest = 0;
    const auto& v = run.state.velocity;
    for (std::size_t i = 0; i < v.size(); i += 3)
      fastest =
          std::max(fastest, std::sqrt(v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]));
    std::ofstream(run.config.output.dir + "/speed.csv", std::ios::app)
        << std::setprecision(17) << run.state.time << ',' << fastest << '\n';
  }
  NamedArrays saved_state() const override { return {{"speed.next", {schedule_.next()}}}; }

 private:
  double every_;
  OutputSchedule schedule_;
};

const bool registered = [] {
  register_output({"speed",
                   {"speed_every"},
                   [](const OptionReader& r) {
                     auto o = std::make_shared<SpeedLogOptions>();
                     o->every = r.positive("speed_every", 0.0);
                     return o;
                   },
                   [](const OutputContext& c) {
                     return std::make_unique<SpeedLog>(output_options<SpeedLogOptions>(c).every);
                   }});
  return true;
}();

const std::string kFalling =
    test::free_block_yaml("gravity: [0, 0, -9.81]\noutput: {every: 0.1, speed_every: 0.02}\n");

TEST(CustomOutput, SpeedLogWritesItsRowsAtItsOwnInterval) {
  ASSERT_TRUE(registered);
  const auto dir = test::scratch_dir("speed");
  Config config = parse_config(kFalling, (dir / "falling.yaml").string());
  config.output.dir = dir.string();
  run_simulation(config, {});
  std::ifstream in(dir / "speed.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "time,max_speed");
  int rows = 0;
  double t, speed;
  char comma;
  while (in >> t >> comma >> speed) {
    // Round-off only: t sums 20 steps of 0.001 per row and v_n sums n = 100 at most of g h
    // (n ε |v| ≈ 2e-14 m/s), the rigid fall's internal forces are those of round-off in the
    // bond vectors; one step late or early would be off by g h = 9.8e-3 m/s.
    EXPECT_NEAR(t, 0.02 * rows, 1e-12) << "row " << rows;
    EXPECT_NEAR(speed, 9.81 * t, 1e-9) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, 6);  // t = 0, 0.02, ..., 0.1
}

TEST(CustomOutput, ItsKeyIsCheckedByItsOwnParser) {
  ASSERT_TRUE(registered);
  const std::string e = test::input_error_message(
      [] { parse_config(kFalling, "falling.yaml", {"output.speed_every=-1"}); });
  EXPECT_NE(e.find("falling.yaml: output.speed_every: must be positive"), std::string::npos) << e;
  const std::string typo = test::input_error_message(
      [] { parse_config(kFalling, "falling.yaml", {"output.sped_every=1"}); });
  EXPECT_NE(typo.find("output.sped_every"), std::string::npos) << typo;
}

}  // namespace
}  // namespace fissure
