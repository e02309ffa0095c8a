#pragma once
// summary.json (docs/output.md): a run's RunSummary as JSON, its keys in the documented order.
#include <string>

#include "app/simulation.hpp"

namespace fissure {

// The text of summary.json: numbers to 9 significant digits (integral ones without a fraction),
// null where a number is not finite, strings escaped by nlohmann-json (invalid UTF-8 replaced).
std::string summary_json(const RunSummary& summary);

// Writes summary_json(summary) to `path` atomically (io/atomic_file.hpp).
void write_summary(const std::string& path, const RunSummary& summary);

}  // namespace fissure
