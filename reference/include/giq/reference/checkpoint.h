#pragma once
// Checkpoints of a render in progress: the film's accumulators, bit for bit, so a resumed
// render continues every pixel's sample sequence exactly where it stopped and ends with the
// same bits as an uninterrupted one.
//
// Format (native byte order; a checkpoint is resumed on the machine that wrote it): the magic
// "giq-checkpoint 2\n", the identity string (scene hash, view, frame and every setting that
// changes the image), elapsed seconds, width, height, the pixel accumulators and first-hit
// layers as stored in memory, and a 64-bit FNV-1a hash of everything before it, so a torn
// or corrupt file is detected rather than resumed.

#include <filesystem>
#include <optional>
#include <string>

#include "giq/reference/film.h"

namespace giq::reference {

struct Checkpoint {
  Film film;
  double elapsed_seconds = 0.0;  // render time spent before the checkpoint
};

// Written atomically (giq::write_atomically): a kill at any moment leaves the previous
// checkpoint or the new one, never a partial file.
void write_checkpoint(const std::filesystem::path& path, const Film& film, const std::string& identity,
                      double elapsed_seconds);

// nullopt when there is no file. Throws InputError when the file is corrupt or belongs to a
// different render (its identity differs: the message names both).
std::optional<Checkpoint> read_checkpoint(const std::filesystem::path& path, const std::string& identity);

}  // namespace giq::reference
