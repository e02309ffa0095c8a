#pragma once
// When an output is due: every `interval` seconds of simulated time, from `first`. Each output
// observer keeps one and checkpoints its next time.
namespace fissure {

class OutputSchedule {
 public:
  OutputSchedule(double interval, double first) : interval_(interval), next_(first) {}
  // True when t has reached the next time (within `tolerance`); the next one is then set.
  bool due(double t, double tolerance) {
    if (t + tolerance < next_) return false;
    next_ += interval_;
    return true;
  }
  double next() const { return next_; }
  void set_next(double next) { next_ = next; }

 private:
  double interval_;
  double next_;
};

}  // namespace fissure
