#include "app/checkpoint.hpp"

#include <filesystem>
#include <regex>

#include "core/error.hpp"
#include "io/checkpoint_file.hpp"

namespace fissure {

Config checkpoint_config(const CheckpointReader& checkpoint, const std::string& dir) {
  Config config = parse_config(checkpoint.text("config"), checkpoint.text("config.file"));
  config.output.dir = dir;
  return config;
}

void trim_output(const std::string& dir, double frames, double probes_bytes) {
  const std::filesystem::path probes = std::filesystem::path(dir) / "probes.csv";
  if (!std::filesystem::exists(probes) || std::filesystem::file_size(probes) < probes_bytes)
    throw InputError(probes.string(), "",
                     "shorter than when the checkpoint was written: cannot resume without the "
                     "rows before it");
  std::filesystem::resize_file(probes, static_cast<std::uintmax_t>(probes_bytes));
  std::filesystem::remove(std::filesystem::path(dir) / "summary.json");
  static const std::regex frame(R"((particles|surface|tets)_(\d{6})\.(vtu|obj))");
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, m, frame) && std::stod(m[2]) >= frames)
      std::filesystem::remove(entry.path());
  }
}

}  // namespace fissure
