#pragma once
// The scalar a picture colours particles by, and the colour map.
#include <array>
#include <string>
#include <vector>

#include "io/vtu_reader.hpp"

namespace fissure {

// Per particle: damage and dilatation as written, velocity and displacement as magnitudes.
// A frame without the field (damage of a run without fracture) gives zeros.
std::vector<double> field_values(const VtuGrid& grid, const std::string& field);

// Whether the field is signed (its colour range is symmetric about zero).
bool field_signed(const std::string& field);

// Cool-to-warm diverging map (Moreland): t in [0, 1] from blue through grey to red.
std::array<double, 3> cool_warm(double t);

}  // namespace fissure
