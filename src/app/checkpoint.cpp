#include "app/checkpoint.hpp"

#include "core/error.hpp"
#include "io/checkpoint_file.hpp"

namespace fissure {

Config checkpoint_config(const CheckpointReader& checkpoint, const std::string& dir) {
  Config config = parse_config(checkpoint.text("config"), checkpoint.text("config.file"));
  config.output.dir = dir;
  return config;
}

void check_loop_sections(const CheckpointReader& checkpoint) {
  for (const char* old :
       {"run.schedule", "run.ledger", "run.frames", "run.frame_times", "run.probes_bytes"})
    if (checkpoint.has(old))
      throw InputError(
          checkpoint.path(), old,
          "written by an earlier version of fissure, which kept the run loop's state in "
          "positional arrays; this version reads named sections (ledger.*, probes.*, frames.*, "
          "checkpoint.*, energy_growth.*) and cannot resume it: go on with the version that "
          "wrote it, or run the config again");
}

}  // namespace fissure
