// Config parsing: defaults, overrides and key-path errors.
#include <gtest/gtest.h>

#include "integrators/arkode_settings.hpp"
#include "integrators/petsc_newton_settings.hpp"
#include "integrators/registry.hpp"
#include "scene/config.hpp"
#include "support/error_message.hpp"

namespace fissure {
namespace {

const char* kMinimal =
    "time: {end: 1.0, dt: auto}\n"
    "bodies:\n"
    "  - name: bar\n"
    "    geometry: {box: {min: [0, 0, 0], max: [1, 0.1, 0.1]}}\n"
    "    resolution: 0.025\n"
    "    material: {density: 1000, bulk_modulus: 5.0e6, shear_modulus: 5.0e6}\n";

// The integrator options a config's parsers made.
PetscNewtonSettings petsc_newton(const Config& c) {
  return options_of<PetscNewtonSettings>(c.integrator);
}
ArkodeSettings arkode(const Config& c) { return options_of<ArkodeSettings>(c.integrator); }

std::string error_of(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  return test::input_error_message([&] { parse_config(yaml, "scene.yaml", overrides); });
}

TEST(Config, DefaultsAreFilledIn) {
  const Config c = parse_config(kMinimal, "dir/scene.yaml");
  EXPECT_EQ(c.name, "scene");
  EXPECT_TRUE(c.time.dt_auto);
  EXPECT_EQ(c.integrator.type, "symplectic_euler");
  EXPECT_DOUBLE_EQ(c.bodies[0].horizon, 1.45);
  EXPECT_EQ(c.bodies[0].material.model, "lps");
  EXPECT_EQ(c.output.dir, "out/scene");
  EXPECT_DOUBLE_EQ(c.output.every, 0.01);
  EXPECT_DOUBLE_EQ(c.damping, 0.0);
}

TEST(Config, OverridesReachNestedKeysAndListItems) {
  const Config c = parse_config(kMinimal, "scene.yaml",
                                {"bodies[0].material.density=2000", "time.dt=1e-5",
                                 "integrator.type=velocity_verlet", "bodies.0.horizon=3"});
  EXPECT_DOUBLE_EQ(c.bodies[0].material.density, 2000);
  EXPECT_FALSE(c.time.dt_auto);
  EXPECT_DOUBLE_EQ(c.time.dt, 1e-5);
  EXPECT_EQ(c.integrator.type, "velocity_verlet");
  EXPECT_DOUBLE_EQ(c.bodies[0].horizon, 3);
}

TEST(Config, UnknownKeySuggestsNearest) {
  const std::string e = error_of(kMinimal, {"bodies[0].material.densty=5"});
  EXPECT_NE(e.find("scene.yaml: bodies[0].material.densty: unknown key; did you mean 'density'?"),
            std::string::npos)
      << e;
}

TEST(Config, WrongTypeNamesKey) {
  const std::string e = error_of(kMinimal, {"bodies[0].resolution=fine"});
  EXPECT_NE(e.find("bodies[0].resolution: expected a number, got 'fine'"), std::string::npos) << e;
}

TEST(Config, NonPositiveValuesAreRejected) {
  for (const char* key :
       {"bodies[0].material.density", "bodies[0].material.bulk_modulus",
        "bodies[0].material.shear_modulus", "bodies[0].resolution", "bodies[0].horizon"}) {
    const std::string e = error_of(kMinimal, {std::string(key) + "=0"});
    EXPECT_NE(e.find(std::string(key) + ": must be positive"), std::string::npos) << e;
  }
}

TEST(Config, MalformedYamlGivesLine) {
  const std::string e = error_of("time: {end: 1.0\nbodies: [");
  EXPECT_NE(e.find("scene.yaml: not valid YAML (line"), std::string::npos) << e;
}

// yaml-cpp stops at its depth limit with the message "bad file"; the error says what is wrong.
TEST(Config, DeeplyNestedYamlIsNamed) {
  const std::string e = error_of("time: " + std::string(100000, '['));
  EXPECT_NE(e.find("scene.yaml: not valid YAML (line 1, column"), std::string::npos) << e;
  EXPECT_NE(e.find("levels deep"), std::string::npos) << e;
}

// petsc_newton's solver keys: defaults, choices read into their enums, bad values named.
TEST(Config, NewtonSolverKeys) {
  const Config d = parse_config(kMinimal, "scene.yaml", {"integrator.type=petsc_newton"});
  using P = PetscNewtonSettings::Preconditioner;
  using K = PetscNewtonSettings::Krylov;
  EXPECT_EQ(petsc_newton(d).preconditioner, P::automatic);
  EXPECT_EQ(petsc_newton(d).krylov, K::automatic);
  EXPECT_EQ(petsc_newton(d).factor_precision, FactorPrecision::half);
  EXPECT_TRUE(petsc_newton(d).reuse_factor);
  EXPECT_DOUBLE_EQ(petsc_newton(d).refresh_contraction, 0.25);
  EXPECT_EQ(petsc_newton(d).refresh_iterations, 6);
  EXPECT_EQ(petsc_newton(d).refresh_krylov, 40);
  EXPECT_EQ(petsc_newton(d).newton_test, PetscNewtonSettings::NewtonTest::automatic);
  const Config c =
      parse_config(kMinimal, "scene.yaml",
                   {"integrator.type=petsc_newton", "integrator.scheme=sdirk4",
                    "integrator.preconditioner=gamg", "integrator.krylov=gmres",
                    "integrator.reuse_factor=false", "integrator.refresh_contraction=0.5",
                    "integrator.refresh_iterations=3", "integrator.refresh_krylov=100",
                    "integrator.factor_precision=double", "integrator.newton_test=local_error"});
  EXPECT_EQ(petsc_newton(c).scheme, PetscNewtonSettings::Scheme::sdirk4);
  EXPECT_EQ(petsc_newton(c).preconditioner, P::gamg);
  EXPECT_EQ(petsc_newton(c).krylov, K::gmres);
  EXPECT_FALSE(petsc_newton(c).reuse_factor);
  EXPECT_DOUBLE_EQ(petsc_newton(c).refresh_contraction, 0.5);
  EXPECT_EQ(petsc_newton(c).refresh_iterations, 3);
  EXPECT_EQ(petsc_newton(c).refresh_krylov, 100);
  EXPECT_EQ(petsc_newton(c).factor_precision, FactorPrecision::full);
  EXPECT_EQ(petsc_newton(c).newton_test, PetscNewtonSettings::NewtonTest::local_error);
  const Config nearest =
      parse_config(kMinimal, "scene.yaml",
                   {"integrator.type=petsc_newton", "integrator.preconditioner=nearest"});
  EXPECT_EQ(petsc_newton(nearest).preconditioner, P::nearest);
  EXPECT_EQ(petsc_newton(
                parse_config(kMinimal, "scene.yaml",
                             {"integrator.type=petsc_newton", "integrator.factor_precision=half"}))
                .factor_precision,
            FactorPrecision::half);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"integrator.preconditioner=ilu", "integrator.preconditioner"},
      {"integrator.krylov=bicg", "integrator.krylov"},
      {"integrator.factor_precision=quarter", "integrator.factor_precision"},
      {"integrator.refresh_contraction=1", "integrator.refresh_contraction: must be in (0, 1)"},
      {"integrator.refresh_iterations=2.5", "integrator.refresh_iterations: must be a whole"},
      {"integrator.scheme=sdirk5", "integrator.scheme"},
      {"integrator.newton_test=energy", "integrator.newton_test"},
      {"integrator.newton_test=local_error",
       "integrator.newton_test: 'local_error' needs a scheme with an embedded error estimate "
       "(esdirk4 or sdirk4), not backward_euler"}};
  for (const auto& [override, message] : bad) {
    const std::string e = error_of(kMinimal, {"integrator.type=petsc_newton", override});
    EXPECT_NE(e.find("scene.yaml: " + message), std::string::npos) << override << ": " << e;
  }
  const std::string other = error_of(kMinimal, {"integrator.preconditioner=scalar"});
  EXPECT_NE(other.find("is an option of petsc_newton"), std::string::npos) << other;
  // arkode reads the three keys of factor reuse (docs/integrators.md); explicit types do not.
  const Config a =
      parse_config(kMinimal, "scene.yaml",
                   {"integrator.type=arkode", "integrator.reuse_factor=false",
                    "integrator.refresh_krylov=7", "integrator.factor_precision=double"});
  EXPECT_FALSE(arkode(a).reuse_factor);
  EXPECT_EQ(arkode(a).refresh_krylov, 7);
  EXPECT_EQ(arkode(a).factor_precision, FactorPrecision::full);
  EXPECT_EQ(
      arkode(parse_config(kMinimal, "scene.yaml", {"integrator.type=arkode"})).factor_precision,
      FactorPrecision::half);
  // arkode's reuse is opt-in (it did not pay where measured); petsc_newton's is on (above).
  EXPECT_FALSE(
      arkode(parse_config(kMinimal, "scene.yaml", {"integrator.type=arkode"})).reuse_factor);
  EXPECT_TRUE(arkode(parse_config(kMinimal, "scene.yaml",
                                  {"integrator.type=arkode", "integrator.reuse_factor=true"}))
                  .reuse_factor);
  // arkode's preconditioner: tangent or nearest (auto by size); petsc_newton's others are not its.
  EXPECT_EQ(arkode(parse_config(kMinimal, "scene.yaml",
                                {"integrator.type=arkode", "integrator.preconditioner=nearest"}))
                .preconditioner,
            ArkodeSettings::Preconditioner::nearest);
  EXPECT_EQ(arkode(parse_config(kMinimal, "scene.yaml", {"integrator.type=arkode"})).preconditioner,
            ArkodeSettings::Preconditioner::automatic);
  const std::string gamg =
      error_of(kMinimal, {"integrator.type=arkode", "integrator.preconditioner=gamg"});
  EXPECT_NE(gamg.find("scene.yaml"), std::string::npos) << gamg;
  EXPECT_NE(gamg.find("integrator.preconditioner"), std::string::npos) << gamg;
  EXPECT_NE(gamg.find("nearest"), std::string::npos) << gamg;
  const std::string explicit_type = error_of(kMinimal, {"integrator.reuse_factor=false"});
  EXPECT_NE(explicit_type.find("is an option of petsc_newton and arkode"), std::string::npos)
      << explicit_type;
}

// petsc_newton static ramps the loads over integrator.steps increments of time.dt: a time.dt
// that reaches time.end in fewer is refused (naming both keys), one that takes as many or more
// (the loads then stay at full) is not.
TEST(Config, StaticLoadRampMustFitInTheRun) {
  const std::vector<std::string> static_4 = {"integrator.type=petsc_newton",
                                             "integrator.scheme=static", "integrator.steps=4"};
  auto with_dt = [&](const std::string& dt) {
    std::vector<std::string> overrides = static_4;
    overrides.push_back("time.dt=" + dt);
    return error_of(kMinimal, overrides);
  };
  for (const char* dt : {"1.0", "0.3334"}) {
    const std::string e = with_dt(dt);
    EXPECT_NE(e.find("scene.yaml: time.dt: "), std::string::npos) << dt << ": " << e;
    EXPECT_NE(e.find("integrator.steps = 4"), std::string::npos) << dt << ": " << e;
  }
  EXPECT_NE(with_dt("1.0").find("in 1 load increment(s)"), std::string::npos);
  EXPECT_NE(with_dt("0.3334").find("end at 0.75 of the load"), std::string::npos);
  // 1e-40 takes 1e40 steps, more than a long holds: the check compares without counting them
  // (UBSan found the cast); the run's own step limit refuses such a time.dt.
  for (const char* dt : {"auto", "0.25", "0.25000000001", "0.125", "1e-40"})
    EXPECT_EQ(with_dt(dt), "") << dt;
  // Other schemes have no ramp: a step of time.end is theirs to take.
  EXPECT_EQ(error_of(kMinimal, {"integrator.type=petsc_newton", "integrator.scheme=newmark",
                                "integrator.steps=4", "time.dt=1.0"}),
            "");
}

TEST(Config, ConstraintNeedsFixOrVelocity) {
  const std::string e = error_of(
      std::string(kMinimal) + "constraints:\n  - {region: {box: {min: [0,0,0], max: [1,1,1]}}}\n");
  EXPECT_NE(e.find("constraints[0]: give either fix: true or velocity"), std::string::npos) << e;
}

TEST(Config, RotatingConstraintNeedsItsCenter) {
  const std::string box = "constraints:\n  - {region: {box: {min: [0,0,0], max: [1,1,1]}}, ";
  std::string e = error_of(std::string(kMinimal) + box + "angular_velocity: [1, 0, 0]}\n");
  EXPECT_NE(e.find("constraints[0].center: missing"), std::string::npos) << e;
  e = error_of(std::string(kMinimal) + box + "fix: true, center: [0, 0, 0]}\n");
  EXPECT_NE(e.find("constraints[0].center: only used with angular_velocity"), std::string::npos)
      << e;
  const Config c = parse_config(
      std::string(kMinimal) + box + "angular_velocity: [0, 0, 2], center: [0.5, 0, 0]}\n",
      "scene.yaml");
  ASSERT_EQ(c.constraints.size(), 1u);
  EXPECT_TRUE(c.constraints[0].rotates());
  EXPECT_DOUBLE_EQ(c.constraints[0].angular_velocity[2], 2.0);
  EXPECT_DOUBLE_EQ(c.constraints[0].center[0], 0.5);
}

}  // namespace
}  // namespace fissure
