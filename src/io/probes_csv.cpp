#include "io/probes_csv.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace fissure {

std::vector<std::vector<int>> probe_members(const Config& config, const Particles& particles,
                                            int first, int end) {
  std::vector<std::vector<int>> all;
  for (const Probe& probe : config.probes) {
    std::vector<int> members;
    for (int i = first; i < end; ++i)
      if (probe.region.contains(&particles.reference[3 * i])) members.push_back(i);
    all.push_back(std::move(members));
  }
  return all;
}

void check_probe_members(const Config& config, const std::vector<double>& members) {
  for (std::size_t p = 0; p < config.probes.size(); ++p)
    if (members.at(p) == 0)
      throw InputError(config.file, fmt::format("probes[{}].region", p),
                       fmt::format("probe '{}' contains no particle", config.probes[p].name));
}

ProbesCsv::ProbesCsv(const std::string& path, const Config& config,
                     const std::vector<std::string>& extra_columns, bool append)
    : file_(path, append ? OutputFile::Mode::append : OutputFile::Mode::truncate) {
  if (append) return;
  std::ostream& out = file_.stream();
  out << "time,kinetic_energy,elastic_energy";
  for (const auto& probe : config.probes)
    for (const char* column : {"pos_x", "pos_y", "pos_z", "disp_x", "disp_y", "disp_z"})
      out << ',' << probe.name << '.' << column;
  for (const std::string& column : extra_columns) out << ',' << column;
  out << '\n';
  file_.flush();
}

void ProbesCsv::write_row(double time, double kinetic_energy, double elastic_energy,
                          const std::vector<std::vector<double>>& members,
                          const std::vector<double>& extra) {
  std::ostream& out = file_.stream();
  out << fmt::format("{:.9g},{:.9g},{:.9g}", time, kinetic_energy, elastic_energy);
  for (const std::vector<double>& values : members) {
    double pos[3] = {0, 0, 0}, disp[3] = {0, 0, 0};
    for (std::size_t m = 0; m + 6 <= values.size(); m += 6)
      for (int k = 0; k < 3; ++k) {
        pos[k] += values[m + k];
        disp[k] += values[m + 3 + k];
      }
    const double inv = 1.0 / static_cast<double>(values.size() / 6);
    for (double v : pos) out << fmt::format(",{:.9g}", v * inv);
    for (double v : disp) out << fmt::format(",{:.9g}", v * inv);
  }
  for (double v : extra) out << fmt::format(",{:.9g}", v);
  out << '\n';
  file_.flush();
}

}  // namespace fissure
