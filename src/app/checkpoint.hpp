#pragma once
// Resuming a run (fissure run --resume OUT_DIR): the config a checkpoint was written with, and the
// output folder taken back to the checkpoint.
#include <string>

#include "scene/config.hpp"

namespace fissure {

class CheckpointReader;

// The config of the run that wrote `checkpoint`, writing into `dir`.
Config checkpoint_config(const CheckpointReader& checkpoint, const std::string& dir);

// Drops what a run wrote after its checkpoint: frames numbered `frames` and up (particles,
// surface, tets), rows of probes.csv past its first `probes_bytes` bytes, and summary.json.
void trim_output(const std::string& dir, double frames, double probes_bytes);

}  // namespace fissure
