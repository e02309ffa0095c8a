#pragma once
// probes.csv: one row per probe time, flushed as it goes. Columns: time, kinetic_energy,
// elastic_energy, then per probe NAME.pos_{x,y,z} and NAME.disp_{x,y,z} (means over the
// particles whose reference position lies in the probe's region).
#include <fstream>
#include <string>
#include <vector>

#include "scene/config.hpp"
#include "scene/particles.hpp"

namespace fissure {

class ProbesCsv {
 public:
  // Throws InputError if a probe region holds no particle.
  ProbesCsv(const std::string& path, const Config& config, const Particles& particles);
  void write_row(double time, double kinetic_energy, double elastic_energy,
                 const std::vector<double>& position);

 private:
  std::ofstream out_;
  const Particles& particles_;
  std::vector<std::vector<int>> members_;
};

}  // namespace fissure
