#pragma once
// output.dir/checkpoint.bin every output.checkpoint_every (io/checkpoint_file.hpp): everything the
// run needs to go on from this step, the config, the state, the broken bonds, the saved state of
// the post-step, the dynamics, the integrator and every observer (app/observer.hpp). The last
// output of its step, so a resumed run has had that step's output.
#include <functional>

#include "app/observer.hpp"
#include "app/output_schedule.hpp"

namespace fissure {

class CheckpointOutput : public Observer {
 public:
  // `observers_state` gives the saved state of every observer, this one's included.
  CheckpointOutput(const Config& config, std::function<NamedArrays()> observers_state);
  std::string name() const override { return "checkpoint"; }
  void resume(const RunParts& run, const NamedArrays& state) override;
  void after_step(const RunParts& run, const Step& step) override;
  NamedArrays saved_state() const override;
  // Where to go on from after output failed: the last checkpoint's time and the command, or
  // that there is none.
  std::string resume_advice(const std::string& dir) const;

 private:
  void write(const RunParts& run) const;

  std::function<NamedArrays()> observers_state_;
  double interval_;
  OutputSchedule schedule_;
  double last_time_ = -1;  // −1: no checkpoint written (or resumed from) yet
};

}  // namespace fissure
