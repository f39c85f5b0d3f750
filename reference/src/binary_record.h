#pragma once
// Internal: the film's binary files (checkpoints, shard parts) field by field, in native byte
// order, every read bounds-checked against the file so that a hostile length never allocates
// or reads past its end.

#include <cstring>
#include <string>
#include <type_traits>

#include "giq/base/error.h"

namespace giq::reference {

template <class T>
void put(std::string& out, const T& v) {
  static_assert(std::is_arithmetic_v<T>);
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
inline void put_string(std::string& out, const std::string& s) {
  put(out, uint64_t(s.size()));
  out += s;
}

// Reads data[0, end); a read past `end` throws InputError(file, field, truncated).
class RecordReader {
 public:
  RecordReader(const std::string& data, size_t end, std::string file, std::string field, std::string truncated)
      : data_(data), end_(end), file_(std::move(file)), field_(std::move(field)), truncated_(std::move(truncated)) {}
  template <class T>
  T get() {
    static_assert(std::is_arithmetic_v<T>);
    T v;
    bytes(&v, sizeof(T));
    return v;
  }
  void bytes(void* dst, size_t n) {
    if (n == 0) return;  // dst may be an empty vector's null data(), which memcpy must not get
    if (n > end_ - pos_) fail(truncated_);
    std::memcpy(dst, data_.data() + pos_, n);
    pos_ += n;
  }
  std::string string() {
    const uint64_t n = get<uint64_t>();
    if (n > end_ - pos_) fail("a string of " + std::to_string(n) + " bytes runs past the end of the file");
    std::string s(size_t(n), '\0');
    bytes(s.data(), size_t(n));
    return s;
  }
  size_t pos() const { return pos_; }
  size_t left() const { return end_ - pos_; }
  [[noreturn]] void fail(const std::string& why) const { throw InputError(file_, field_, why); }

 private:
  const std::string& data_;
  size_t end_;
  std::string file_, field_, truncated_;
  size_t pos_ = 0;
};

}  // namespace giq::reference
