#include "mesh/crack_faces.hpp"

#include <algorithm>

namespace fissure {

void CrackFaces::add(int face, int opposite) {
  if (state_[face] != kIntact) return;
  state_[face] = state_[opposite] = kActive;
  set_.push_back(face);
  ++total_;
}

void CrackFaces::retire(int face, int opposite) {
  if (state_[face] != kActive) return;
  state_[face] = state_[opposite] = kRetired;
  ++retired_;
}

void CrackFaces::end_pass() {
  if (retired_ > 0)
    set_.erase(
        std::remove_if(set_.begin(), set_.end(), [&](int f) { return state_[f] != kActive; }),
        set_.end());
  retired_ = 0;
  fresh_begin_ = set_.size();
}

}  // namespace fissure
