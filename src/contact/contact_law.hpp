#pragma once
// What a contact with a rigid collider is made of (contact/collider_shape.hpp): the particles'
// contact law, the forces' sums, and the contacts an implicit step's friction holds fixed.
#include <array>

namespace fissure {

using Point = std::array<double, 3>;

// What the particles bring to a contact with one collider (contact/contact_particles.hpp) and
// Coulomb's μ; the particles [begin, end) it acts on (a rank's rows, or all).
struct ContactLaw {
  int begin, end;
  const double* reach;      // contact radius per particle: ½ V^(1/3), less its overlap at load
  const double* stiffness;  // penalty stiffness per particle [N/m]
  double friction;
};

// The forces of one collider on the particles at one evaluation, summed: the normal (penalty)
// forces and the friction forces on the particles. The reaction on the collider is −(both).
struct ContactSums {
  Point normal{0, 0, 0};
  Point friction{0, 0, 0};
};

// A contact at the start of an implicit step, which the step's friction potential holds fixed
// (lagged): the particle, μ times its normal force [N], the outward normal, and the anchor of the
// particle's stage velocity (z − start)/span.
struct LaggedContact {
  int particle;
  double limit;
  double normal[3];
  double start[3];
};

}  // namespace fissure
