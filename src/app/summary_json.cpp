#include "app/summary_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"

namespace fissure {

namespace {

using Json = nlohmann::ordered_json;

// The 9 significant digits summary.json has always carried; an integral value as an integer,
// null where JSON has no number (inf, nan).
Json number(double v) {
  if (!std::isfinite(v)) return nullptr;
  const double rounded = std::stod(fmt::format("{:.9g}", v));
  if (rounded == std::trunc(rounded) && std::abs(rounded) < 9.0e15)
    return static_cast<long long>(rounded);
  return rounded;
}

Json table(const std::vector<std::pair<std::string, double>>& entries) {
  Json t = Json::object();
  for (const auto& [name, value] : entries) t[name] = number(value);
  return t;
}

}  // namespace

std::string summary_json(const RunSummary& s) {
  Json j = Json::object();
  j["status"] = s.status;
  j["particles"] = s.particles;
  j["ranks"] = s.ranks;
  j["bonds"] = s.bonds;
  j["steps"] = s.steps;
  j["dt"] = number(s.dt);
  j["stable_dt"] = number(s.stable_dt);
  j["wall_seconds"] = number(s.wall_seconds);
  j["seconds_per_step"] = number(s.seconds_per_step);
  j["setup_seconds"] = number(s.setup_seconds);
  j["peak_rss_mb"] = number(s.peak_rss_mb);
  j["energy_drift"] = number(s.energy_drift);
  j["max_speed"] = number(s.max_speed);
  j["broken_bonds"] = s.broken_bonds;
  j["fragments"] = s.fragments;
  j["post_steps"] = s.post_steps;
  j["force_evaluations"] = s.force_evaluations;
  j["integrator"] = s.integrator;
  j["energy"] = table(s.energy);
  j["message"] = s.message;
  j["integrator_statistics"] = table(s.integrator_statistics);
  j["model_statistics"] = table(s.model_statistics);
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

void write_summary(const std::string& path, const RunSummary& summary) {
  write_atomically(path, [&](std::ostream& out) { out << summary_json(summary); });
}

}  // namespace fissure
