#pragma once
// The techniques a giq binary registers, read from `giq realtime --list --json` run as a child
// process (the binary may be another build than this one): what `giq sweep`, `giq gate
// calibrate` and `giq results` enumerate.

#include <filesystem>
#include <vector>

#include "sweep_plan.h"

namespace giq::cli {

// The command and its output go to `log`. Throws InputError when it fails or prints no
// technique.
std::vector<TechniqueParameters> list_techniques(const std::filesystem::path& giq, const std::filesystem::path& log);

}  // namespace giq::cli
