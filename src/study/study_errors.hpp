#pragma once
// The error of a run against the reference at the compare times: the paper's metric
// |x_p − x_p^ref| / d (d the diagonal of the reference's bounding box at t = 0, §6), as the
// maximum and the RMS over particles and compare times, and the largest probe-position error
// over d.
#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace fissure {

struct StudyError {
  double max = std::numeric_limits<double>::quiet_NaN();
  double rms = std::numeric_limits<double>::quiet_NaN();
  double probe = std::numeric_limits<double>::quiet_NaN();
  // The same probe error over the reference's amplitude: the largest distance of a reference
  // probe from its position at t = 0 (the motion's amplitude, not the body's size).
  double probe_amplitude = std::numeric_limits<double>::quiet_NaN();
};

// Probe positions from a probes.csv: per probe name, one [x, y, z] per row, and the row times.
struct ProbePositions {
  std::vector<double> time;
  std::map<std::string, std::vector<std::array<double, 3>>> position;
};

// Reads the `<probe>.pos_x/y/z` columns of a probes.csv; InputError naming the file otherwise.
ProbePositions read_probe_positions(const std::string& csv);

// The largest distance of any probe from its first row's position, over all rows [m].
double probe_amplitude(const ProbePositions& probes);

// Diagonal of the bounding box of the particles in frame 0 of a run folder.
double frame_diagonal(const std::string& run_dir);

// Particle errors from frames 1..frames of both folders (frame k at the k-th compare time),
// probe errors at `times`; reference_dir empty: probes only, against `reference_probes`.
StudyError study_error(const std::string& run_dir, const std::string& reference_dir,
                       const ProbePositions& reference_probes, const std::vector<double>& times,
                       double diagonal);

}  // namespace fissure
