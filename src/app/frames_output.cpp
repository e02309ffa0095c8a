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

void FramesOutput::start(const RunParts& run) {
  run.ranks.write([&] {
    if (!run.ranks.root()) return;
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      const std::string extension = entry.path().extension().string();
      const bool frame =
          name.rfind("particles_", 0) == 0 && (extension == ".vtu" || extension == ".pvtu");
      if (frame || name == "particles.pvd") std::filesystem::remove(entry.path());
    }
    remove_surface_output(dir_);
  });
}

void FramesOutput::resume(const RunParts& run, const NamedArrays& state) {
  schedule_.set_next(saved_number(state, "frames.next"));
  last_time_ = saved_number(state, "frames.last_time");
  frame_times_ = saved_array(state, "frames.times");
  if (!run.ranks.root()) return;  // the root keeps the folder
  const double frames = static_cast<double>(frame_times_.size());
  // a frame's files: one rank's .vtu, or several ranks' pieces (_pR.vtu) and their .pvtu
  static const std::regex frame(R"((particles|surface|tets)_(\d{6})(_p\d+)?\.(vtu|pvtu|obj))");
  for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, m, frame) && std::stod(m[2]) >= frames)
      std::filesystem::remove(entry.path());
  }
  // the frames before the checkpoint, as written on however many ranks wrote them
  std::vector<std::pair<double, std::string>> listed;
  for (std::size_t k = 0; k < frame_times_.size(); ++k) {
    const std::string joined = fmt::format("particles_{:06d}.pvtu", k);
    const bool pieces = std::filesystem::exists(dir_ + "/" + joined);
    listed.emplace_back(frame_times_[k], pieces ? joined : fmt::format("particles_{:06d}.vtu", k));
  }
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
  const RunRanks& ranks = run.ranks;
  // this rank's rows: every row on one rank
  const int begin = ranks.begin(), end = ranks.end(), n = end - begin;
  auto rows = [begin, end](const std::vector<double>& values, int width) {
    return std::vector<double>(values.begin() + std::ptrdiff_t(width) * begin,
                               values.begin() + std::ptrdiff_t(width) * end);
  };
  std::vector<double> displacement(3 * std::size_t(n));
  for (int k = 0; k < 3 * n; ++k)
    displacement[k] = state.position[3 * begin + k] - particles.reference[3 * begin + k];
  const std::vector<double>* damage_or_null = run.post_step.damage();
  const std::vector<double> damage =
      damage_or_null ? rows(*damage_or_null, 1) : std::vector<double>(n, 0.0);
  std::vector<double> dilatation(particles.count());
  run.model.dilatation(state.position.data(), dilatation.data());  // θ at the frame's y
  dilatation = rows(dilatation, 1);
  const std::vector<double> position = rows(state.position, 3), velocity = rows(state.velocity, 3);
  const std::vector<int> body(particles.body.begin() + begin, particles.body.begin() + end);
  const std::vector<PointField> fields = {{"displacement", 3, &displacement},
                                          {"velocity", 3, &velocity},
                                          {"damage", 1, &damage},
                                          {"dilatation", 1, &dilatation}};
  const int index = static_cast<int>(frame_times_.size());
  std::string file = fmt::format("particles_{:06d}.vtu", index);
  if (ranks.distributed()) {
    // each rank writes its rows as a piece; the root joins them in a .pvtu (docs/mpi.md)
    auto piece = [index](int rank) { return fmt::format("particles_{:06d}_p{}.vtu", index, rank); };
    ranks.write(
        [&] { write_particles_vtu(dir_ + "/" + piece(ranks.rank()), position, fields, &body); });
    file = fmt::format("particles_{:06d}.pvtu", index);
    std::vector<std::string> pieces;
    for (int r = 0; r < ranks.size(); ++r) pieces.push_back(piece(r));
    ranks.write([&] {
      if (!ranks.root()) return;
      write_particles_pvtu(dir_ + "/" + file, pieces, fields, true);
      pvd_.add(state.time, file);
    });
  } else {
    write_particles_vtu(dir_ + "/" + file, position, fields, &body);
    pvd_.add(state.time, file);
  }
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
