#include "study/study_errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/vtu_reader.hpp"

namespace fissure {

namespace {

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(line);
  for (std::string part; std::getline(in, part, separator);) parts.push_back(part);
  return parts;
}

std::string frame_file(const std::string& dir, int index) {
  return fmt::format("{}/particles_{:06d}.vtu", dir, index);
}

// The row of `p` at time t (within 1e-6 of the spacing of `times`), or -1.
long row_at(const ProbePositions& p, double t, double spacing) {
  for (std::size_t k = 0; k < p.time.size(); ++k)
    if (std::abs(p.time[k] - t) <= 1e-6 * spacing) return static_cast<long>(k);
  return -1;
}

}  // namespace

ProbePositions read_probe_positions(const std::string& csv) {
  std::ifstream in(csv);
  if (!in) throw InputError(csv, "", "cannot open the probes CSV");
  std::string line;
  if (!std::getline(in, line)) throw InputError(csv, "", "empty file: expected a header line");
  const auto header = split(line, ',');
  if (header.empty() || header[0] != "time")
    throw InputError(csv, "", "the first column must be `time`");
  ProbePositions p;
  std::map<std::string, std::array<int, 3>> columns;
  for (std::size_t c = 0; c < header.size(); ++c)
    for (int k = 0; k < 3; ++k) {
      const std::string suffix = std::string(".pos_") + "xyz"[k];
      const std::string& h = header[c];
      if (h.size() > suffix.size() &&
          h.compare(h.size() - suffix.size(), suffix.size(), suffix) == 0) {
        auto& entry =
            columns
                .try_emplace(h.substr(0, h.size() - suffix.size()), std::array<int, 3>{-1, -1, -1})
                .first->second;
        entry[k] = static_cast<int>(c);
      }
    }
  for (const auto& [name, cols] : columns)
    if (*std::min_element(cols.begin(), cols.end()) < 0)
      throw InputError(csv, name, "needs all three columns .pos_x, .pos_y and .pos_z");
  for (long row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const auto cells = split(line, ',');
    try {
      if (cells.size() != header.size()) throw std::invalid_argument("column count");
      p.time.push_back(std::stod(cells[0]));
      for (const auto& [name, cols] : columns)
        p.position[name].push_back(
            {std::stod(cells[cols[0]]), std::stod(cells[cols[1]]), std::stod(cells[cols[2]])});
    } catch (const std::exception&) {
      throw InputError(csv, fmt::format("line {}", row),
                       fmt::format("expected {} numbers separated by commas", header.size()));
    }
  }
  return p;
}

double frame_diagonal(const std::string& run_dir) {
  const VtuGrid grid = read_vtu(frame_file(run_dir, 0));
  double low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (long i = 0; i < grid.point_count(); ++i)
    for (int k = 0; k < 3; ++k) {
      low[k] = std::min(low[k], grid.points[3 * i + k]);
      high[k] = std::max(high[k], grid.points[3 * i + k]);
    }
  return std::sqrt(std::pow(high[0] - low[0], 2) + std::pow(high[1] - low[1], 2) +
                   std::pow(high[2] - low[2], 2));
}

StudyError study_error(const std::string& run_dir, const std::string& reference_dir,
                       const ProbePositions& reference_probes, const std::vector<double>& times,
                       double diagonal) {
  StudyError e;
  const double spacing = times.size() > 1 ? times[1] - times[0] : times.front();
  if (!reference_dir.empty()) {
    double worst = 0, squares = 0;
    long count = 0;
    for (std::size_t k = 1; k <= times.size(); ++k) {
      const VtuGrid run = read_vtu(frame_file(run_dir, static_cast<int>(k)));
      const VtuGrid ref = read_vtu(frame_file(reference_dir, static_cast<int>(k)));
      if (run.points.size() != ref.points.size())
        throw RunError(fmt::format("{}: frame {} has {} particles, the reference {}", run_dir, k,
                                   run.point_count(), ref.point_count()));
      for (long i = 0; i < run.point_count(); ++i) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c)
          d2 += std::pow(run.points[3 * i + c] - ref.points[3 * i + c], 2);
        const double error = std::sqrt(d2) / diagonal;
        worst = std::max(worst, error);
        squares += error * error;
        ++count;
      }
    }
    e.max = worst;
    e.rms = std::sqrt(squares / std::max(count, 1L));
  }
  const ProbePositions run = read_probe_positions(run_dir + "/probes.csv");
  double worst = -1;
  for (const auto& [name, reference] : reference_probes.position) {
    const auto it = run.position.find(name);
    if (it == run.position.end()) continue;
    for (double t : times) {
      const long a = row_at(run, t, spacing), b = row_at(reference_probes, t, spacing);
      if (a < 0 || b < 0) continue;
      double d2 = 0;
      for (int c = 0; c < 3; ++c) d2 += std::pow(it->second[a][c] - reference[b][c], 2);
      worst = std::max(worst, std::sqrt(d2));
    }
  }
  if (worst >= 0) {
    e.probe = worst / diagonal;
    const double amplitude = probe_amplitude(reference_probes);
    if (amplitude > 0) e.probe_amplitude = worst / amplitude;
  }
  return e;
}

double probe_amplitude(const ProbePositions& probes) {
  double amplitude = 0;
  for (const auto& [name, rows] : probes.position)
    for (const auto& x : rows) {
      double d2 = 0;
      for (int c = 0; c < 3; ++c) d2 += std::pow(x[c] - rows.front()[c], 2);
      amplitude = std::max(amplitude, std::sqrt(d2));
    }
  return amplitude;
}

}  // namespace fissure
