#include "giq/reference/checkpoint.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <type_traits>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/hash.h"
#include "binary_record.h"

namespace giq::reference {
namespace {

constexpr char kMagic[] = "giq-checkpoint 2\n";
static_assert(std::is_trivially_copyable_v<PixelAccumulator> && std::is_trivially_copyable_v<PixelAux>);

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const Film& film, const std::string& identity,
                      double elapsed_seconds) {
  std::string out(kMagic);
  put(out, uint64_t(identity.size()));
  out += identity;
  put(out, elapsed_seconds);
  put(out, int32_t(film.width));
  put(out, int32_t(film.height));
  out.append(reinterpret_cast<const char*>(film.pixels.data()), film.pixels.size() * sizeof(PixelAccumulator));
  out.append(reinterpret_cast<const char*>(film.aux.data()), film.aux.size() * sizeof(PixelAux));
  put(out, Hasher().add(out).value());
  write_file_atomically(path, out);
}

std::optional<Checkpoint> read_checkpoint(const std::filesystem::path& path, const std::string& identity) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string file = path.string();
  const size_t magic = sizeof(kMagic) - 1;
  if (data.size() < magic + sizeof(uint64_t) || data.compare(0, magic, kMagic) != 0)
    throw InputError(file, "checkpoint", "not a giq checkpoint (expected it to start with 'giq-checkpoint 2'; checkpoints of older giq versions cannot be resumed)");
  uint64_t stored_hash;
  std::memcpy(&stored_hash, data.data() + data.size() - sizeof(uint64_t), sizeof(uint64_t));
  if (Hasher().add(data.data(), data.size() - sizeof(uint64_t)).value() != stored_hash)
    throw InputError(file, "checkpoint", "checksum mismatch: the file is corrupt; delete it to start over");
  RecordReader r(data, data.size(), path.string(), "checkpoint", "file is truncated; delete it to start over");
  std::string skip(magic, '\0');
  r.bytes(skip.data(), magic);
  const uint64_t n = r.get<uint64_t>();
  if (n > data.size()) throw InputError(file, "checkpoint", "identity length " + std::to_string(n) + " exceeds the file");
  std::string stored(size_t(n), '\0');
  r.bytes(stored.data(), size_t(n));
  if (stored != identity)
    throw InputError(file, "checkpoint",
                     "belongs to a different render: it has '" + stored + "', this render is '" + identity +
                         "'; use the same scene and settings, or delete the checkpoint");
  Checkpoint c;
  c.elapsed_seconds = r.get<double>();
  const int32_t w = r.get<int32_t>(), h = r.get<int32_t>();
  if (w < 1 || h < 1 || w > 65536 || h > 65536)
    throw InputError(file, "checkpoint", "image size " + std::to_string(w) + "x" + std::to_string(h) + " is invalid");
  // The declared size against the file before the film is allocated: 65536^2 pixels would
  // otherwise ask for hundreds of gigabytes.
  const size_t pixels = size_t(w) * size_t(h);
  const size_t pixel_bytes = pixels * sizeof(PixelAccumulator), aux_bytes = pixels * sizeof(PixelAux);
  if (data.size() != r.pos() + pixel_bytes + aux_bytes + sizeof(uint64_t))
    throw InputError(file, "checkpoint", "size does not match a " + std::to_string(w) + "x" + std::to_string(h) + " film");
  c.film = Film(w, h);
  r.bytes(c.film.pixels.data(), pixel_bytes);
  r.bytes(c.film.aux.data(), aux_bytes);
  return c;
}

}  // namespace giq::reference
