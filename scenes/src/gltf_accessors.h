#pragma once
// Bounds-checked reading of glTF accessors (glTF 2.0 spec, 3.6 "Accessors"), with the glTF
// path of every problem in the error.

#include <tiny_gltf.h>

#include <initializer_list>
#include <string>
#include <vector>

namespace giq::scenes::gltf {

struct Context {
  const std::string& file;
  const tinygltf::Model& model;
  // Values read so far over all accessors: primitives may share accessors, so a small file
  // can ask for the same large data many times; the total is bounded (read_accessor).
  mutable size_t values_read = 0;
  [[noreturn]] void fail(const std::string& field, const std::string& message) const;
};

std::string index_path(const std::string& array, size_t i);  // "accessors[3]"

// What a use of an accessor accepts (a semantic's row of the spec's attribute table).
struct AccessorRule {
  std::vector<int> types;  // TINYGLTF_TYPE_*
  bool float_components = true;      // FLOAT
  bool normalized_unsigned = false;  // normalized UNSIGNED_BYTE/UNSIGNED_SHORT
  bool normalized_signed = false;    // normalized BYTE/SHORT
  bool unsigned_integers = false;    // UNSIGNED_BYTE/SHORT/INT, not normalized (indices)
};

struct AccessorData {
  int components = 0;
  size_t count = 0;
  std::vector<double> values;  // count * components; normalized integers already mapped to [0,1]/[-1,1]
};

// Reads accessor `index`, referenced from `field`. Checks the index, type and component type
// against `rule`, bounds against the buffer view and buffer, sparse substitution, and that
// every float is finite. Throws InputError.
AccessorData read_accessor(const Context& ctx, int index, const std::string& field, const AccessorRule& rule);

}  // namespace giq::scenes::gltf
