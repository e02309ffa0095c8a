#pragma once
// probes.csv: one row per probe time, flushed as it goes. Columns: time, kinetic_energy,
// elastic_energy, then per probe NAME.pos_{x,y,z} and NAME.disp_{x,y,z} (means over the
// particles whose reference position lies in the probe's region), then the extra columns (the
// energy ledger's).
#include <string>
#include <vector>

#include "io/output_file.hpp"
#include "scene/config.hpp"
#include "scene/particles.hpp"

namespace fissure {

// The particles of each probe (config.probes), whose reference position lies in its region;
// throws InputError if a probe region holds no particle. Touches no file.
std::vector<std::vector<int>> probe_members(const Config& config, const Particles& particles);

class ProbesCsv {
 public:
  // `members` from probe_members(). With `append` the rows go after those already in the file (a
  // resumed run) and no header is written. Each row reaches the file as it is written;
  // OutputError when the file refuses it.
  ProbesCsv(const std::string& path, const Config& config, const Particles& particles,
            std::vector<std::vector<int>> members, const std::vector<std::string>& extra_columns,
            bool append = false);
  void write_row(double time, double kinetic_energy, double elastic_energy,
                 const std::vector<double>& position, const std::vector<double>& extra);

 private:
  const Particles& particles_;
  OutputFile file_;
  std::vector<std::vector<int>> members_;
};

}  // namespace fissure
