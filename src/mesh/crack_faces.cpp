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
  if (state_[face] == kActive) state_[face] = state_[opposite] = kRetired;
}

void CrackFaces::end_pass() {
  set_.erase(std::remove_if(set_.begin(), set_.end(), [&](int f) { return state_[f] != kActive; }),
             set_.end());
  fresh_begin_ = set_.size();
}

}  // namespace fissure
