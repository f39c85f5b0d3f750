#pragma once
// The checks every command makes on the paths it will write, before any work: a render of
// hours must not fail at its end because --out names a folder, and no input may be
// overwritten by an output (`giq reference --scene s.gltf --out s.gltf`, `giq score --test
// out/abs_error.exr --out out`). Each failure is an InputError naming the option.

#include <filesystem>
#include <string>
#include <vector>

namespace giq::cli {

// Empty input paths (options not given) are skipped.
// A file the command writes: not an existing folder, no regular file where one of its folders
// would be, and not the same file as any input.
void check_output_file(const std::filesystem::path& out, const std::vector<std::filesystem::path>& inputs,
                       const std::string& option);

// A folder the command writes into: not an existing regular file, no regular file where one of
// its parent folders would be, and no input inside it (the command's files could replace it).
void check_output_folder(const std::filesystem::path& out, const std::vector<std::filesystem::path>& inputs,
                         const std::string& option);

// Whether `p` lies in `folder` (at any depth, or is it) once both are resolved: links and ".."
// followed as far as the paths exist.
bool path_inside(const std::filesystem::path& p, const std::filesystem::path& folder);

}  // namespace giq::cli
