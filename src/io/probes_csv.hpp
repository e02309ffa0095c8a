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

// The particles [first, end) of each probe (config.probes), whose reference position lies in
// its region. Touches no file.
std::vector<std::vector<int>> probe_members(const Config& config, const Particles& particles,
                                            int first, int end);
// Throws InputError for the first probe with no member: `members` counts each probe's members
// in the whole scene.
void check_probe_members(const Config& config, const std::vector<double>& members);

class ProbesCsv {
 public:
  // With `append` the rows go after those already in the file (a resumed run) and no header is
  // written. Each row reaches the file as it is written; OutputError when the file refuses it.
  ProbesCsv(const std::string& path, const Config& config,
            const std::vector<std::string>& extra_columns, bool append = false);
  // `members`: per probe, each member's position and displacement (6 values, in the order of
  // the members' particles), of which the row holds the means.
  void write_row(double time, double kinetic_energy, double elastic_energy,
                 const std::vector<std::vector<double>>& members, const std::vector<double>& extra);

 private:
  OutputFile file_;
};

}  // namespace fissure
