#pragma once
// Atomic file output: write to a temporary file beside the target, then rename(2) over it.
// A reader sees either the old file or the complete new one, never a partial write; a
// writer that throws or a process that dies leaves the final name untouched.

#include <filesystem>
#include <functional>
#include <string_view>

namespace giq {

// Calls write(tmp_path) to produce the file under a temporary name in the same directory,
// fsyncs it and renames it to `path`. If write throws, the temporary is removed and the
// exception propagates. Throws InputError when the directory cannot be written.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

// Convenience for byte content.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace giq
