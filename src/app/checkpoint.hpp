#pragma once
// Resuming a run (fissure run --resume OUT_DIR): the config a checkpoint was written with, and the
// check that its run-loop sections are the named ones this version reads.
#include <string>

#include "scene/config.hpp"

namespace fissure {

class CheckpointReader;

// The config of the run that wrote `checkpoint`, writing into `dir`.
Config checkpoint_config(const CheckpointReader& checkpoint, const std::string& dir);

// Throws InputError naming the file when `checkpoint` keeps the run loop's state in the
// positional sections of earlier versions (run.schedule, run.ledger, ...), which this version
// does not read: each observer of the loop now saves its own named sections.
void check_loop_sections(const CheckpointReader& checkpoint);

}  // namespace fissure
