#pragma once
// Finding and running the external programs `fissure render` hands work to (POV-Ray,
// ImageMagick, ffmpeg).
#include <string>
#include <vector>

namespace fissure {

// Full path of `name` on PATH, or "" when it is not installed.
std::string find_program(const std::string& name);

// Runs `argv` (argv[0] looked up on PATH) in folder `cwd`, its stdout and stderr appended to
// `log`; returns its exit status, or -1 when it could not be started or was killed.
int run_program(const std::vector<std::string>& argv, const std::string& cwd,
                const std::string& log);

}  // namespace fissure
