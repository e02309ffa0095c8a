// fissure: run a scene, or describe it.
#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/info.hpp"
#include "app/simulation.hpp"
#include "core/error.hpp"
#include "scene/config.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "Fissure: peridynamics for elastoplastic solids that bend, yield, crack and shatter"};
  app.require_subcommand(1);
  std::string config_path, out_dir;
  std::vector<std::string> overrides;

  auto* run = app.add_subcommand("run", "simulate a scene, writing output as it goes");
  run->add_option("config", config_path, "scene file (YAML)")->required();
  run->add_option("--out", out_dir, "output folder (overrides output.dir)");
  run->add_option("--set", overrides, "override a config key: key.path=value (repeatable)")
      ->allow_extra_args(false);

  auto* info = app.add_subcommand("info", "print particles, bonds, stable dt and effects");
  info->add_option("config", config_path, "scene file (YAML)")->required();
  info->add_option("--set", overrides, "override a config key: key.path=value (repeatable)")
      ->allow_extra_args(false);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    fissure::Config config = fissure::load_config(config_path, overrides);
    if (!out_dir.empty()) config.output.dir = out_dir;
    if (*info) {
      fissure::print_info(config);
      return 0;
    }
    fissure::RunOptions options;
    options.progress = isatty(fileno(stderr));
    const auto s = fissure::run_simulation(config, options);
    fmt::print(
        "{}: {} particles, {} bonds, {} steps of {:.3g} s in {:.2f} s ({:.3g} s/step), "
        "energy drift {:.2e}, output in {}\n",
        config.name, s.particles, s.bonds, s.steps, s.dt, s.wall_seconds, s.seconds_per_step,
        s.energy_drift, config.output.dir);
    return 0;
  } catch (const fissure::InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const fissure::RunError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {  // e.g. an output folder that cannot be created
    fmt::print(stderr, "error: {}\n", e.what());
    return 3;
  }
}
