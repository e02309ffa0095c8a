#include "app/simulation.hpp"

#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/checkpoint.hpp"
#include "app/energy.hpp"
#include "app/energy_ledger.hpp"
#include "app/summary_json.hpp"
#include "core/error.hpp"
#include "fracture/fragments.hpp"
#include "fracture/post_step.hpp"
#include "integrators/integrator.hpp"
#include "io/checkpoint_file.hpp"
#include "io/probes_csv.hpp"
#include "io/surface_writer.hpp"
#include "io/vtu_writer.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Index of the first particle whose position or velocity is not finite, or −1.
int first_nonfinite(const State& s) {
  const int n = static_cast<int>(s.position.size() / 3);
  int first = n;
#pragma omp parallel for reduction(min : first) schedule(static)
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.position[3 * i + k]) || !std::isfinite(s.velocity[3 * i + k]))
        first = std::min(first, i);
  return first == n ? -1 : first;
}

// The largest particle speed |v_i|.
double max_speed(const std::vector<double>& velocity) {
  double largest = 0;
  const int n = static_cast<int>(velocity.size() / 3);
#pragma omp parallel for reduction(max : largest) schedule(static)
  for (int i = 0; i < n; ++i) {
    const double* v = &velocity[3 * i];
    largest = std::max(largest, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return std::sqrt(largest);
}

// time.dt: auto: the explicit estimate times time.safety; for a static solve, time.end over
// its load increments; for an adaptive integrator, the frame interval (its largest step).
double automatic_time_step(const Config& config, const Integrator& integrator, double stable_dt) {
  const IntegratorSettings& s = config.integrator;
  if (const int ramp = s.options ? s.options->load_increments() : 0) return config.time.end / ramp;
  if (integrator.adaptive()) return std::min(config.output.every, config.time.end);
  return config.time.safety * stable_dt;
}

// Removes the files an earlier run left in `dir`, so frames of two runs never mix.
void clear_previous_output(const std::string& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const bool frame = name.rfind("particles_", 0) == 0 && entry.path().extension() == ".vtu";
    if (frame || name == "particles.pvd" || name == "probes.csv" || name == "summary.json")
      std::filesystem::remove(entry.path());
  }
  remove_surface_output(dir);
}

class Simulation {
 public:
  Simulation(const Config& config, const RunOptions& options);
  // Steps to time.end; output that cannot be written stops the run (stop_writing).
  RunSummary run();

 private:
  RunSummary run_steps();
  void write_frame();
  void sample_energy();
  // Adds the step's work and losses to the ledger; `kinetic` is K at the end of the step.
  void book_step(double h, const std::vector<double>& before, double kinetic);
  // Stops the run (RunError) when energy that no load put in exceeds
  // integrator.energy_growth_limit of the energy scale for 10 steps in a row: K + losses −
  // (E(0) + work) bounds the balance from below because Π ≥ 0, so it needs no energy evaluation.
  void check_energy_growth(double dt, double kinetic);
  // Writes a last probes.csv row (unless the state is non-finite) and summary.json with `status`
  // and `message`, then throws RunError(message).
  [[noreturn]] void stop(const std::string& status, const std::string& message);
  // Output that cannot be written: summary.json (where it still can be written) records status
  // failed, and the RunError names the file, the reason and the checkpoint to go on from.
  [[noreturn]] void stop_writing(const OutputError& error);
  void finish_summary();
  // Writes output.dir/checkpoint.bin: everything the run needs to go on from this step.
  void write_checkpoint();
  // Takes the run back to the checkpoint's step; the output after it is dropped.
  void resume(const CheckpointReader& checkpoint);
  void report_progress(Clock::time_point start, bool final);

  const Config& config_;
  RunOptions options_;
  Clock::time_point setup_start_;
  std::unique_ptr<Integrator> integrator_;
  Scene scene_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Dynamics> dynamics_;
  std::unique_ptr<PostStep> post_step_;
  std::unique_ptr<ProbesCsv> probes_;
  std::unique_ptr<PvdIndex> pvd_;
  std::unique_ptr<SurfaceWriter> surface_writer_;  // only with output.surface or output.tets
  State state_;
  RunSummary summary_;
  int frame_ = 0;
  EnergyLedger ledger_;
  double last_sample_time_ = -1;
  bool sampled_ = false;
  // 1e-12 Σ m|g||x|: below this the work of gravity is lost to the round-off of positions (a
  // first adaptive step of 1e-12 s moves nothing), so energy this small is never "growth".
  double round_off_energy_ = 0;
  int excess_steps_ = 0;                   // consecutive steps over integrator.energy_growth_limit
  std::vector<double> previous_position_;  // y at the start of the step, for the load work
  // Output schedule: the next probe row, frame and checkpoint are due at these times.
  double next_probe_ = 0, next_frame_ = 0, next_checkpoint_ = 0, last_frame_time_ = 0;
  double last_checkpoint_time_ = -1;  // −1: no checkpoint written (or resumed from) yet
  std::vector<double> frame_times_;
};

Simulation::Simulation(const Config& config, const RunOptions& options)
    : config_(config), options_(options), setup_start_(Clock::now()) {
  integrator_ = make_integrator(config.integrator, config.file);
  scene_ = build_scene(config);
  model_ = make_model(scene_);
  dynamics_ = std::make_unique<Dynamics>(scene_, *model_);
  integrator_->check(*dynamics_);  // before the output folder is touched
  post_step_ = std::make_unique<PostStep>(scene_, *model_, true);
  summary_.integrator = config.integrator.type;
  summary_.particles = scene_.particles.count();
  summary_.bonds = static_cast<long>(scene_.families.directed_bonds() / 2);
  summary_.stable_dt = model_->stable_time_step();
  summary_.dt = config.time.dt_auto ? automatic_time_step(config, *integrator_, summary_.stable_dt)
                                    : config.time.dt;
  if (integrator_->explicit_step() && !config.time.dt_auto && config.time.dt > summary_.stable_dt) {
    const std::string reason =
        fmt::format("{:.3g} s exceeds the stable estimate {:.3g} s of the explicit integrator '{}'",
                    config.time.dt, summary_.stable_dt, config.integrator.type);
    if (!config.integrator.allow_unstable_dt)
      throw InputError(config.file, "time.dt",
                       reason +
                           "; use dt: auto, a step below the estimate, an implicit "
                           "integrator (petsc_newton, arkode), or "
                           "integrator.allow_unstable_dt: true to run it anyway");
    fmt::print(stderr, "warning: {}: time.dt = {}; the run may blow up\n", config.file, reason);
  }
  constexpr double max_steps = 1e9;
  if (config.time.end / summary_.dt > max_steps)
    throw InputError(
        config.file, config.time.dt_auto ? "time.end" : "time.dt",
        fmt::format("time.end / dt = {:.3g} steps (dt = {:.3g} s) is more than {:.0g}; "
                    "check resolution, moduli and density",
                    config.time.end / summary_.dt, summary_.dt, max_steps));
  std::filesystem::create_directories(config.output.dir);
  if (!options.resume) clear_previous_output(config.output.dir);
  if (options.resume)
    trim_output(config.output.dir, options.resume->number("run.frames"),
                options.resume->number("run.probes_bytes"));
  probes_ = std::make_unique<ProbesCsv>(config.output.dir + "/probes.csv", config, scene_.particles,
                                        EnergyLedger::names(), options.resume != nullptr);
  pvd_ = std::make_unique<PvdIndex>(config.output.dir + "/particles.pvd");
  if (config.output.embedded_mesh())
    surface_writer_ = std::make_unique<SurfaceWriter>(config.output.dir, config.output.surface,
                                                      config.output.tets);
  const Vec3& g = config.gravity;
  const double g_norm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  for (int i = 0; i < scene_.particles.count(); ++i) {
    const double* x = &scene_.particles.reference[3 * i];
    round_off_energy_ += 1e-12 * scene_.particles.mass[i] * g_norm *
                         std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }
  state_.position = scene_.particles.reference;
  state_.velocity = scene_.particles.velocity;
  dynamics_->constrain_velocity(0.0, state_.velocity.data());
  next_checkpoint_ = config.output.checkpoint_every;
  if (options.resume) resume(*options.resume);
}

void Simulation::write_checkpoint() {
  CheckpointWriter w;
  w.add("config", config_.source);
  w.add("config.file", config_.file);
  w.add("run.time", std::vector<double>{state_.time});
  w.add("run.steps", std::vector<double>{double(summary_.steps)});
  w.add("run.frames", std::vector<double>{double(frame_)});
  w.add("run.frame_times", frame_times_);
  w.add("run.schedule",
        std::vector<double>{next_probe_, next_frame_, next_checkpoint_, last_frame_time_,
                            last_sample_time_, summary_.max_speed});
  const std::string probes = config_.output.dir + "/probes.csv";
  std::error_code error;
  const auto probes_bytes = std::filesystem::file_size(probes, error);
  if (error)
    throw OutputError(probes, "cannot read its size for the checkpoint: " + error.message());
  w.add("run.probes_bytes", std::vector<double>{double(probes_bytes)});
  w.add("run.ledger", ledger_.numbers());
  w.add("state.position", state_.position);
  w.add("state.velocity", state_.velocity);
  w.add("state.broken", post_step_->broken());
  for (const NamedArrays& part :
       {post_step_->saved_state(), dynamics_->saved_state(), integrator_->saved_state()})
    for (const auto& [name, values] : part) w.add(name, values);
  w.write(config_.output.dir + "/checkpoint.bin");
  last_checkpoint_time_ = state_.time;
}

void Simulation::resume(const CheckpointReader& c) {
  const std::vector<double> position = c.doubles("state.position");
  if (position.size() != state_.position.size())
    throw InputError(c.path(), "state.position",
                     fmt::format("{} particles, but the scene has {}", position.size() / 3,
                                 state_.position.size() / 3));
  state_.position = position;
  state_.velocity = c.doubles("state.velocity");
  state_.time = c.number("run.time");
  last_checkpoint_time_ = state_.time;
  summary_.steps = static_cast<long>(c.number("run.steps"));
  frame_ = static_cast<int>(c.number("run.frames"));
  frame_times_ = c.doubles("run.frame_times");
  const std::vector<double> schedule = c.doubles("run.schedule");
  if (schedule.size() != 6) throw InputError(c.path(), "run.schedule", "expected 6 numbers");
  next_probe_ = schedule[0];
  next_frame_ = schedule[1];
  next_checkpoint_ = schedule[2];
  last_frame_time_ = schedule[3];
  last_sample_time_ = schedule[4];
  summary_.max_speed = schedule[5];
  ledger_ = EnergyLedger::from_numbers(c.doubles("run.ledger"));
  sampled_ = true;
  NamedArrays post_step = c.arrays("post_step.");
  for (auto& array : c.arrays("model.")) post_step.push_back(std::move(array));
  post_step_->restore_state(scene_, post_step, c.bytes("state.broken"));
  // The mesh was split afresh from the broken bonds; its vertices start from the particles.
  if (EmbeddedMesh* mesh = post_step_->embedded_mesh()) mesh->place(state_.position.data());
  dynamics_->restore_state(c.arrays("dynamics."));
  integrator_->restore_state(c.arrays("integrator."));
  std::vector<std::pair<double, std::string>> frames;
  for (std::size_t k = 0; k < frame_times_.size(); ++k)
    frames.emplace_back(frame_times_[k], fmt::format("particles_{:06d}.vtu", k));
  pvd_->reset(frames);
  if (surface_writer_) surface_writer_->reset(frame_times_);
}

void Simulation::write_frame() {
  const int n = scene_.particles.count();
  std::vector<double> displacement(3 * n);
  for (int k = 0; k < 3 * n; ++k)
    displacement[k] = state_.position[k] - scene_.particles.reference[k];
  const std::vector<double> undamaged(post_step_->damage() ? 0 : n, 0.0);
  const std::vector<double>& damage = post_step_->damage() ? *post_step_->damage() : undamaged;
  std::vector<double> dilatation(n);
  model_->dilatation(state_.position.data(), dilatation.data());
  const std::string file = fmt::format("particles_{:06d}.vtu", frame_++);
  write_particles_vtu(config_.output.dir + "/" + file, state_.position,
                      {{"displacement", 3, &displacement},
                       {"velocity", 3, &state_.velocity},
                       {"damage", 1, &damage},
                       {"dilatation", 1, &dilatation}},
                      &scene_.particles.body);
  pvd_->add(state_.time, file);
  frame_times_.push_back(state_.time);
  if (EmbeddedMesh* mesh = post_step_->embedded_mesh()) {
    mesh->place(state_.position.data());
    surface_writer_->write(frame_ - 1, state_.time, *mesh, damage, scene_.particles.body);
  }
}

void Simulation::sample_energy() {
  ledger_.kinetic = kinetic_energy(scene_.particles.mass, state_.velocity);
  ledger_.elastic = model_->elastic_energy(state_.position.data());
  if (!sampled_) {
    ledger_.initial = ledger_.kinetic + ledger_.elastic;
    sampled_ = true;
  }
  summary_.max_speed = std::max(summary_.max_speed, max_speed(state_.velocity));
  ledger_.scale = std::max({ledger_.scale, ledger_.kinetic + std::abs(ledger_.elastic),
                            std::abs(ledger_.gravity_work) + std::abs(ledger_.constraint_work) +
                                std::abs(ledger_.collider_work)});
  std::vector<double> columns;
  for (const auto& [name, value] : ledger_.entries()) columns.push_back(value);
  probes_->write_row(state_.time, ledger_.kinetic, ledger_.elastic, state_.position, columns);
  last_sample_time_ = state_.time;
}

void Simulation::book_step(double h, const std::vector<double>& before, double kinetic) {
  const Dynamics::Work work = dynamics_->load_work(before.data(), state_.position.data());
  ledger_.gravity_work += work.gravity;
  ledger_.constraint_work += work.constraints;
  ledger_.collider_work += work.colliders;
  ledger_.contact_loss -= work.self_contact;
  ledger_.damping_loss += h * 2.0 * config_.damping * kinetic;
  ledger_.plastic_dissipation = post_step_->released().plastic;
  ledger_.fracture_release = post_step_->released().fracture;
}

void Simulation::check_energy_growth(double dt, double kinetic) {
  const double limit = config_.integrator.energy_growth_limit;
  if (limit <= 0) return;
  const double work = ledger_.gravity_work + ledger_.constraint_work + ledger_.collider_work;
  const double losses = ledger_.damping_loss + ledger_.contact_loss + ledger_.plastic_dissipation +
                        ledger_.fracture_release;
  const double excess = kinetic + losses - (ledger_.initial + work);
  const double budget =
      std::max({ledger_.scale,
                std::abs(ledger_.initial) + std::abs(ledger_.gravity_work) +
                    std::abs(ledger_.constraint_work) + std::abs(ledger_.collider_work),
                round_off_energy_, 1e-300});
  // A load's work can be booked a step late (velocity Verlet at a first contact), so the excess
  // must last: a growing mode stays above the limit, a late booking drops below it again.
  constexpr int kSteps = 10;
  excess_steps_ = excess > limit * budget || !std::isfinite(excess) ? excess_steps_ + 1 : 0;
  if (excess_steps_ < kSteps) return;
  const std::string what = fmt::format(
      "energy grew without a load to account for it at step {} (t = {:.6g} s): kinetic energy "
      "{:.3g} J exceeds the initial energy plus the work put in ({:.3g} J) by {:.3g} times the "
      "run's energy scale (integrator.energy_growth_limit = {:g})",
      summary_.steps, state_.time, kinetic, ledger_.initial + work - losses, excess / budget,
      limit);
  const std::string advice =
      integrator_->explicit_step()
          ? fmt::format(
                "the explicit integrator '{}' is unstable at dt = {:.3g} s; the stable "
                "step estimate is {:.3g} s: use time.dt: auto or a time.dt of at most "
                "{:.3g} s",
                config_.integrator.type, dt, summary_.stable_dt, summary_.stable_dt)
          : fmt::format(
                "the integrator '{}' put energy in at dt = {:.3g} s: try a smaller "
                "time.dt (the explicit stable estimate is {:.3g} s)",
                config_.integrator.type, dt, summary_.stable_dt);
  stop("unstable", fmt::format("{}; {}. Outputs up to this point are kept in {}", what, advice,
                               config_.output.dir));
}

void Simulation::finish_summary() {
  summary_.energy_drift = ledger_.balance_error();
  summary_.energy = ledger_.entries();
  summary_.energy.insert(summary_.energy.begin(), {{"kinetic", ledger_.kinetic},
                                                   {"elastic", ledger_.elastic},
                                                   {"initial", ledger_.initial},
                                                   {"scale", ledger_.scale},
                                                   {"balance", ledger_.balance()}});
  summary_.wall_seconds = seconds_since(setup_start_);
  summary_.peak_rss_mb = peak_rss_mb();
  summary_.broken_bonds = static_cast<long>(post_step_->broken_bonds());
  summary_.fragments = count_fragments(scene_.families, *model_);
  summary_.post_steps = static_cast<long>(post_step_->calls());
  summary_.force_evaluations = dynamics_->force_evaluations();
  summary_.integrator_statistics = integrator_->statistics();
}

void Simulation::stop(const std::string& status, const std::string& message) {
  // The books and a last probe row at the state the run stopped in, unless it is not finite.
  if (status != "nonfinite" && last_sample_time_ < state_.time) sample_energy();
  summary_.status = status;
  summary_.message = message;
  finish_summary();
  write_summary(config_.output.dir + "/summary.json", summary_);
  throw RunError(message);
}

void Simulation::stop_writing(const OutputError& error) {
  const std::string& dir = config_.output.dir;
  const std::string resume =
      last_checkpoint_time_ >= 0
          ? fmt::format(
                "the last checkpoint (t = {:.6g} s) in {} is intact: with room to write, go "
                "on with `fissure run --resume {}`",
                last_checkpoint_time_, dir, dir)
          : "no checkpoint was written (output.checkpoint_every)";
  std::string message =
      fmt::format("{}; the run stopped at t = {:.6g} s; {}", error.what(), state_.time, resume);
  summary_.status = "failed";
  summary_.message = message;
  finish_summary();
  try {
    write_summary(dir + "/summary.json", summary_);
  } catch (const OutputError& also) {
    message += fmt::format(" ({} could not record it either: {})", also.path(), also.reason());
  }
  throw RunError(message);
}

void Simulation::report_progress(Clock::time_point start, bool final) {
  const double elapsed = seconds_since(start);
  const double rate = summary_.steps / std::max(elapsed, 1e-9);
  const double remaining =
      (config_.time.end - state_.time) * elapsed / std::max(state_.time, 1e-300);
  fmt::print(stderr, "\rt = {:.4g} / {:.4g} s   {:.0f} steps/s   ETA {:.0f} s   {}", state_.time,
             config_.time.end, rate, std::max(remaining, 0.0), final ? "\n" : "");
}

RunSummary Simulation::run() {
  try {
    return run_steps();
  } catch (const OutputError& error) {
    stop_writing(error);
  }
}

RunSummary Simulation::run_steps() {
  const bool adaptive = integrator_->adaptive();
  const double dt = summary_.dt;
  const long steps = steps_to(config_.time.end, dt);
  const double end = config_.time.end;
  summary_.setup_seconds = seconds_since(setup_start_);
  const double tolerance = 1e-9 * dt;
  auto output_due = [&] {
    if (state_.time + tolerance >= next_probe_) {
      sample_energy();
      next_probe_ += config_.output.probe_every;
    }
    if (state_.time + tolerance >= next_frame_) {
      write_frame();
      last_frame_time_ = state_.time;
      next_frame_ += config_.output.every;
    }
    if (config_.output.checkpoint_every > 0 && state_.time + tolerance >= next_checkpoint_ &&
        state_.time > 0) {
      next_checkpoint_ += config_.output.checkpoint_every;
      write_checkpoint();
    }
  };
  // A checkpoint is written last in its step's output_due(): a resumed run has had that step's
  // output (with probe_every below dt the probe schedule stays due and would repeat its row).
  if (!options_.resume) output_due();
  const auto start = Clock::now();
  auto last_report = start;
  double stepping_seconds = 0;
  for (long s = summary_.steps; adaptive ? end - state_.time > 1e-12 * end : s < steps; ++s) {
    const auto step_start = Clock::now();
    // A fixed-step integrator shortens its last step to land on time.end; an adaptive one stops
    // on frame times and time.end, and takes at most dt.
    double h = s + 1 == steps ? std::max(end - state_.time, 1e-12 * dt) : dt;
    if (adaptive) {
      h = std::min(dt, end - state_.time);
      if (next_frame_ - state_.time > tolerance) h = std::min(h, next_frame_ - state_.time);
    }
    previous_position_ = state_.position;
    try {
      h = integrator_->step(*dynamics_, state_, h);
    } catch (const RunError& e) {
      stop("failed", fmt::format("{}. Outputs up to t = {:.6g} s are kept in {}", e.what(),
                                 state_.time, config_.output.dir));
    }
    dynamics_->end_step(h);
    if (post_step_->run(state_.position.data(), state_.velocity.data(), h))
      integrator_->bonds_changed();
    ++summary_.steps;
    if (const int bad = first_nonfinite(state_); bad >= 0) {
      const double* x = &scene_.particles.reference[3 * bad];
      stop("nonfinite",
           fmt::format(
               "state became non-finite at step {} (t = {:.6g} s), first at particle {} of body "
               "'{}' (reference position {:.6g}, {:.6g}, {:.6g}); dt = {:.3g} s, stable estimate "
               "{:.3g} s. Outputs up to this point are kept in {}",
               summary_.steps, state_.time, bad, config_.bodies[scene_.particles.body[bad]].name,
               x[0], x[1], x[2], dt, summary_.stable_dt, config_.output.dir));
    }
    // K once per step, for damping's loss and the energy-growth check, when either needs it.
    const double kinetic = config_.damping > 0 || config_.integrator.energy_growth_limit > 0
                               ? kinetic_energy(scene_.particles.mass, state_.velocity)
                               : 0.0;
    book_step(h, previous_position_, kinetic);
    check_energy_growth(h, kinetic);
    stepping_seconds += seconds_since(step_start);
    output_due();
    if (options_.progress && seconds_since(last_report) > 0.5) {
      report_progress(start, false);
      last_report = Clock::now();
    }
  }
  if (options_.progress) report_progress(start, true);
  if (last_sample_time_ < state_.time) sample_energy();
  if (last_frame_time_ < state_.time) write_frame();
  summary_.seconds_per_step = summary_.steps > 0 ? stepping_seconds / summary_.steps : 0.0;
  finish_summary();
  write_summary(config_.output.dir + "/summary.json", summary_);
  return summary_;
}

}  // namespace

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

RunSummary run_simulation(const Config& config, const RunOptions& options) {
  Simulation simulation(config, options);
  return simulation.run();
}

}  // namespace fissure
