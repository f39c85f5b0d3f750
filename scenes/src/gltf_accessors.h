#pragma once
// Bounds-checked reading of glTF accessors (glTF 2.0 spec, 3.6 "Accessors"), with the glTF
// path of every problem in the error.

#include <tiny_gltf.h>

#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace giq::scenes::gltf {

struct AccessorData {
  int components = 0;
  size_t count = 0;
  std::vector<double> values;  // count * components; normalized integers already mapped to [0,1]/[-1,1]
};

struct Context {
  Context(const std::string& file_, const tinygltf::Model& model_) : file(file_), model(model_) {}
  const std::string& file;
  const tinygltf::Model& model;
  // Values read so far over all accessors: primitives may share accessors, so a small file
  // can ask for the same large data many times; the total is bounded (read_accessor).
  mutable size_t values_read = 0;
  // What was loaded but dropped or approximated: one line per kind, however often it occurs
  // (Scene::warnings).
  mutable std::vector<std::string> warnings;
  // Buffer views decoded from their compressed form (gltf_meshopt.cpp), by view index: they
  // replace the view's bytes wherever it is read.
  std::map<int, std::vector<unsigned char>> decoded_views;
  // Accessors decoded from a Draco-compressed primitive (gltf_draco.cpp), by accessor index,
  // while that primitive is loaded: they replace the accessor's data.
  mutable std::map<int, AccessorData> decoded_accessors;
  [[noreturn]] void fail(const std::string& field, const std::string& message) const;
  // Adds a warning of kind `kind`: the first one keeps `message`; later ones of the same kind
  // only count, and the line says how many there were.
  void warn(const std::string& kind, const std::string& message) const;

 private:
  struct Kind {
    std::string kind, message;
    size_t count;
  };
  mutable std::vector<Kind> warning_kinds_;  // in the order of `warnings`
};

std::string index_path(const std::string& array, size_t i);  // "accessors[3]"

// What a use of an accessor accepts (a semantic's row of the spec's attribute table).
struct AccessorRule {
  std::vector<int> types;  // TINYGLTF_TYPE_*
  bool float_components = true;      // FLOAT
  bool normalized_unsigned = false;  // normalized UNSIGNED_BYTE/UNSIGNED_SHORT
  bool normalized_signed = false;    // normalized BYTE/SHORT
  bool unsigned_integers = false;    // UNSIGNED_BYTE/SHORT/INT, not normalized (indices)
  bool small_integers = false;       // BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT, not normalized
};


// Reads accessor `index`, referenced from `field`. Checks the index, type and component type
// against `rule`, bounds against the buffer view and buffer, sparse substitution, and that
// every float is finite. Throws InputError.
AccessorData read_accessor(const Context& ctx, int index, const std::string& field, const AccessorRule& rule);

}  // namespace giq::scenes::gltf
