#pragma once
// GLSL to SPIR-V with the glslang library, at start-up. Shader sources are embedded in the
// binary at build time (so the GPU-machine runner needs no source tree); GIQ_SHADER_DIR
// points at a source tree to edit shaders without rebuilding. #include "x" resolves against
// the including file's folder, then the shader root (realtime/). SPIR-V is cached on disk by
// the hash of the fully preprocessed text, stage and target, so a changed include or #define
// can never hit a stale entry.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "giq/scenes/features.h"

namespace giq::realtime {

struct ShaderDefine {
  std::string name;
  std::string value = "1";
};

// A shader that does not compile: the first error's file, line and message; what() holds
// "file:line: message" followed by the whole compiler log.
class ShaderError : public std::runtime_error {
 public:
  ShaderError(std::string file, int line, std::string message, const std::string& log);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  std::string message_;
};

// One GIQ_<FEATURE> define per feature the scene has (FeatureSet::names(), upper-cased).
std::vector<ShaderDefine> feature_defines(const scenes::FeatureSet& features);

// Source text of a shader file by its path under realtime/ ("techniques/pt/pt.comp").
std::optional<std::string> shader_source(std::string_view path);

class ShaderCompiler {
 public:
  // cache_dir empty = no disk cache.
  explicit ShaderCompiler(std::filesystem::path cache_dir = default_cache_dir());
  // $GIQ_SHADER_CACHE, else $XDG_CACHE_HOME/giq/spirv, else $HOME/.cache/giq/spirv.
  static std::filesystem::path default_cache_dir();

  // Compiles a shader file; the stage comes from the extension (.comp .vert .frag .geom).
  std::vector<uint32_t> compile(const std::string& path, const std::vector<ShaderDefine>& defines = {});
  // Compiles source text given a name (used in messages and for relative includes).
  std::vector<uint32_t> compile_source(const std::string& name, const std::string& source,
                                       const std::vector<ShaderDefine>& defines = {});

  int cache_hits() const { return cache_hits_; }
  int compilations() const { return compilations_; }

 private:
  std::filesystem::path cache_dir_;
  int cache_hits_ = 0;
  int compilations_ = 0;
};

}  // namespace giq::realtime
