#include "io/probes_csv.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace fissure {

std::vector<std::vector<int>> probe_members(const Config& config, const Particles& particles) {
  std::vector<std::vector<int>> all;
  for (std::size_t p = 0; p < config.probes.size(); ++p) {
    std::vector<int> members;
    for (int i = 0; i < particles.count(); ++i)
      if (config.probes[p].region.contains(&particles.reference[3 * i])) members.push_back(i);
    if (members.empty())
      throw InputError(config.file, fmt::format("probes[{}].region", p),
                       fmt::format("probe '{}' contains no particle", config.probes[p].name));
    all.push_back(std::move(members));
  }
  return all;
}

ProbesCsv::ProbesCsv(const std::string& path, const Config& config, const Particles& particles,
                     std::vector<std::vector<int>> members,
                     const std::vector<std::string>& extra_columns, bool append)
    : particles_(particles),
      file_(path, append ? OutputFile::Mode::append : OutputFile::Mode::truncate),
      members_(std::move(members)) {
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
                          const std::vector<double>& position, const std::vector<double>& extra) {
  std::ostream& out = file_.stream();
  out << fmt::format("{:.9g},{:.9g},{:.9g}", time, kinetic_energy, elastic_energy);
  for (const auto& members : members_) {
    double pos[3] = {0, 0, 0}, disp[3] = {0, 0, 0};
    for (int i : members)
      for (int k = 0; k < 3; ++k) {
        pos[k] += position[3 * i + k];
        disp[k] += position[3 * i + k] - particles_.reference[3 * i + k];
      }
    const double inv = 1.0 / static_cast<double>(members.size());
    for (double v : pos) out << fmt::format(",{:.9g}", v * inv);
    for (double v : disp) out << fmt::format(",{:.9g}", v * inv);
  }
  for (double v : extra) out << fmt::format(",{:.9g}", v);
  out << '\n';
  file_.flush();
}

}  // namespace fissure
