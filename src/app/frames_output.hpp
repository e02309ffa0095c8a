#pragma once
// The frames every output.every: particles_NNNNNN.vtu with particles.pvd, and with output.surface
// or output.tets the embedded mesh's files of the same frame (io/surface_writer.hpp). An output
// of the run loop (app/observer.hpp); an adaptive integrator lands on its times.
#include <memory>

#include "app/observer.hpp"
#include "app/output_schedule.hpp"
#include "io/surface_writer.hpp"
#include "io/vtu_writer.hpp"

namespace fissure {

class FramesOutput : public Observer {
 public:
  explicit FramesOutput(const Config& config);
  std::string name() const override { return "frames"; }
  // Removes the frames, collections and surfaces an earlier run left, so two runs never mix.
  void start(const RunParts& run) override;
  // Removes the frames written after the checkpoint and lists those before it again.
  void resume(const RunParts& run, const NamedArrays& state) override;
  void after_step(const RunParts& run, const Step& step) override;
  double next_stop() const override { return schedule_.next(); }
  // A completed run ends on a frame.
  void finish(const RunParts& run, RunEnd end) override;
  NamedArrays saved_state() const override;

 private:
  void write_frame(const RunParts& run);

  std::string dir_;
  PvdIndex pvd_;
  std::unique_ptr<SurfaceWriter> surface_writer_;  // only with output.surface or output.tets
  OutputSchedule schedule_;
  double last_time_ = 0;             // time of the last frame
  std::vector<double> frame_times_;  // of every frame written, frame k at frame_times_[k]
};

}  // namespace fissure
