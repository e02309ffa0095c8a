#pragma once
// Writes a file completely or not at all: a temporary file beside it, then a rename.
#include <functional>
#include <ostream>
#include <string>

namespace fissure {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace fissure
