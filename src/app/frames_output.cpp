#include "app/frames_output.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <regex>

namespace fissure {

FramesOutput::FramesOutput(const Config& config)
    : dir_(config.output.dir),
      pvd_(config.output.dir + "/particles.pvd"),
      schedule_(config.output.every, 0.0) {
  if (config.output.embedded_mesh())
    surface_writer_ = std::make_unique<SurfaceWriter>(config.output.dir, config.output.surface,
                                                      config.output.tets);
}

void FramesOutput::start(const RunParts&) {
  for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    const bool frame = name.rfind("particles_", 0) == 0 && entry.path().extension() == ".vtu";
    if (frame || name == "particles.pvd") std::filesystem::remove(entry.path());
  }
  remove_surface_output(dir_);
}

void FramesOutput::resume(const RunParts&, const NamedArrays& state) {
  schedule_.set_next(saved_number(state, "frames.next"));
  last_time_ = saved_number(state, "frames.last_time");
  frame_times_ = saved_array(state, "frames.times");
  const double frames = static_cast<double>(frame_times_.size());
  static const std::regex frame(R"((particles|surface|tets)_(\d{6})\.(vtu|obj))");
  for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, m, frame) && std::stod(m[2]) >= frames)
      std::filesystem::remove(entry.path());
  }
  std::vector<std::pair<double, std::string>> listed;
  for (std::size_t k = 0; k < frame_times_.size(); ++k)
    listed.emplace_back(frame_times_[k], fmt::format("particles_{:06d}.vtu", k));
  pvd_.reset(listed);
  if (surface_writer_) surface_writer_->reset(frame_times_);
}

void FramesOutput::after_step(const RunParts& run, const Step&) {
  if (schedule_.due(run.state.time, run.tolerance())) write_frame(run);
}

void FramesOutput::finish(const RunParts& run, RunEnd end) {
  if (end == RunEnd::completed && last_time_ < run.state.time) write_frame(run);
}

void FramesOutput::write_frame(const RunParts& run) {
  const State& state = run.state;
  const Particles& particles = run.scene.particles;
  const int n = particles.count();
  std::vector<double> displacement(3 * n);
  for (int k = 0; k < 3 * n; ++k) displacement[k] = state.position[k] - particles.reference[k];
  const std::vector<double>* damage_or_null = run.post_step.damage();
  const std::vector<double> undamaged(damage_or_null ? 0 : n, 0.0);
  const std::vector<double>& damage = damage_or_null ? *damage_or_null : undamaged;
  std::vector<double> dilatation(n);
  run.model.dilatation(state.position.data(), dilatation.data());  // θ at the frame's y
  const int index = static_cast<int>(frame_times_.size());
  const std::string file = fmt::format("particles_{:06d}.vtu", index);
  write_particles_vtu(dir_ + "/" + file, state.position,
                      {{"displacement", 3, &displacement},
                       {"velocity", 3, &state.velocity},
                       {"damage", 1, &damage},
                       {"dilatation", 1, &dilatation}},
                      &particles.body);
  pvd_.add(state.time, file);
  frame_times_.push_back(state.time);
  if (EmbeddedMesh* mesh = run.post_step.embedded_mesh()) {
    mesh->place(state.position.data());
    surface_writer_->write(index, state.time, *mesh, damage, particles.body);
  }
  last_time_ = state.time;
}

NamedArrays FramesOutput::saved_state() const {
  return {{"frames.next", {schedule_.next()}},
          {"frames.last_time", {last_time_}},
          {"frames.times", frame_times_}};
}

}  // namespace fissure
