// fissure: run a scene, describe it, render a run's frames, or run a work-precision study.
#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "app/checkpoint.hpp"
#include "app/info.hpp"
#include "app/run_ranks.hpp"
#include "app/simulation.hpp"
#include "core/error.hpp"
#include "io/checkpoint_file.hpp"
#include "render/render.hpp"
#include "scene/config.hpp"
#include "scene/render_settings.hpp"
#include "scene/study_config.hpp"
#include "study/study.hpp"

namespace {

// fissure study runs its scenes one after another into one folder: on several ranks each would
// run the whole study into it (docs/mpi.md).
void refuse_several_ranks(const std::string& verb) {
  if (const int ranks = fissure::launched_ranks(); ranks > 1)
    throw fissure::InputError(
        "", "",
        fmt::format("fissure {} was started on {} MPI ranks, but it runs on one: each rank would "
                    "run the whole {} into the same output folder. Run it on one rank; `mpirun "
                    "fissure run` spreads one scene over ranks (docs/mpi.md)",
                    verb, ranks, verb));
}

// Over several ranks every rank reaches the same end: rank 0 speaks for them.
bool speaks() { return fissure::launched_rank() == 0; }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Fissure: peridynamics for elastoplastic solids that bend, yield, crack and shatter"};
  app.require_subcommand(1);
  std::string config_path, out_dir;
  std::vector<std::string> overrides;

  auto* run = app.add_subcommand("run", "simulate a scene, writing output as it goes");
  std::string resume_dir;
  run->add_option("config", config_path, "scene file (YAML)");
  run->add_option("--resume", resume_dir,
                  "go on from the checkpoint in this output folder (output.checkpoint_every)");
  run->add_option("--out", out_dir, "output folder (overrides output.dir)");
  run->add_option("--set", overrides, "override a config key: key.path=value (repeatable)")
      ->allow_extra_args(false);

  auto* info = app.add_subcommand("info", "print particles, bonds, stable dt and effects");
  info->add_option("config", config_path, "scene file (YAML)")->required();
  info->add_option("--set", overrides, "override a config key: key.path=value (repeatable)")
      ->allow_extra_args(false);

  auto* render = app.add_subcommand("render", "turn a run's frames into PNG pictures and a GIF");
  std::string field, run_dir;
  render->add_option("run_dir", run_dir, "the run's output folder")->required();
  render->add_option("--out", out_dir, "folder for the pictures (default: RUN_DIR/render)");
  render->add_option("--config", config_path, "scene file whose render: block applies");
  render->add_option("--field", field, "colour by damage, velocity, displacement or dilatation");
  render->add_option("--set", overrides, "override a config key, e.g. render.every=5")
      ->allow_extra_args(false);

  auto* study = app.add_subcommand(
      "study", "run a work-precision study: error against wall time per integrator");
  study->add_option("study_file", config_path, "study file (YAML, docs/studies.md)")->required();
  study->add_option("--out", out_dir, "output folder (overrides output.dir)");
  study->add_option("--set", overrides, "override a study file key: key.path=value (repeatable)")
      ->allow_extra_args(false);

  // Past a file-size limit (ulimit -f) a write then fails with EFBIG, which the run reports
  // (file, reason, exit code 3), instead of SIGXFSZ killing it without a word.
  if (std::signal(SIGXFSZ, SIG_IGN) == SIG_ERR)
    fmt::print(stderr, "warning: cannot ignore SIGXFSZ: a file-size limit would kill the run\n");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*render) {
      if (!field.empty()) overrides.push_back("render.field=" + field);
      const auto r =
          fissure::render_run(run_dir, fissure::load_render_settings(config_path, overrides),
                              out_dir, isatty(fileno(stderr)));
      fmt::print("rendered {} frames to {} in {:.1f} s{}\n", r.frames, r.folder, r.seconds,
                 r.animation.empty() ? "" : ", animation " + r.animation);
      return 0;
    }
    if (*study) {
      refuse_several_ranks("study");
      fissure::StudyConfig study_config = fissure::load_study(config_path, overrides);
      if (!out_dir.empty()) study_config.output_dir = out_dir;
      const auto s = fissure::run_study(study_config, isatty(fileno(stderr)));
      fmt::print("study: {} runs ({} refused or failed); results.csv, results.md{} in {}\n", s.runs,
                 s.failed, s.plotted ? ", work_precision.png/.svg" : "", s.folder);
      return 0;
    }
    std::unique_ptr<fissure::CheckpointReader> checkpoint;
    if (*run && resume_dir.empty() == config_path.empty())
      throw fissure::InputError("", "", "fissure run takes a scene file or --resume OUT_DIR");
    if (!resume_dir.empty() && !(overrides.empty() && out_dir.empty()))
      throw fissure::InputError("", "",
                                "--resume goes on with the run's own config: no --set, --out");
    if (!resume_dir.empty())
      checkpoint = std::make_unique<fissure::CheckpointReader>(resume_dir + "/checkpoint.bin");
    fissure::Config config = checkpoint ? fissure::checkpoint_config(*checkpoint, resume_dir)
                                        : fissure::load_config(config_path, overrides);
    if (!out_dir.empty()) config.output.dir = out_dir;
    if (*info) {
      if (speaks()) fissure::print_info(config);
      return 0;
    }
    fissure::RunOptions options;
    options.progress = isatty(fileno(stderr));
    options.resume = checkpoint.get();
    const auto s = fissure::run_simulation(config, options);
    if (speaks())
      fmt::print(
          "{}: {} particles, {} bonds, {} steps of {:.3g} s in {:.2f} s ({:.3g} s/step), "
          "energy drift {:.2e}, output in {}\n",
          config.name, s.particles, s.bonds, s.steps, s.dt, s.wall_seconds, s.seconds_per_step,
          s.energy_drift, config.output.dir);
    return 0;
  } catch (const fissure::InputError& e) {
    if (speaks()) fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const fissure::RunError& e) {
    if (speaks()) fmt::print(stderr, "error: {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {  // e.g. an output folder that cannot be created
    if (speaks()) fmt::print(stderr, "error: {}\n", e.what());
    return 3;
  }
}
