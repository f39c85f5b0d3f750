#pragma once
// Content hashing for provenance: a reference EXR records the hash of the scene it was
// rendered from, so a stale golden is detected instead of silently used. Not cryptographic.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace giq {

// 64-bit FNV-1a, incremental (Fowler, Noll, Vo; the published offset basis and prime).
class Hasher {
 public:
  Hasher& add(const void* data, size_t size);
  Hasher& add(std::string_view s) { return add(s.data(), s.size()); }
  uint64_t value() const { return h_; }
  std::string hex() const;  // 16 lowercase hex digits

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace giq
