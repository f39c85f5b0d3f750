#include "giq/realtime/shader.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>

#include "giq/base/atomic_file.h"
#include "giq/base/hash.h"

namespace giq::realtime {

namespace detail {
struct EmbeddedShader {
  const char* path;
  const char* text;
};
extern const EmbeddedShader kEmbeddedShaders[];
extern const size_t kEmbeddedShaderCount;
}  // namespace detail

ShaderError::ShaderError(std::string file, int line, std::string message, const std::string& log)
    : std::runtime_error(file + ":" + std::to_string(line) + ": " + message + "\n" + log),
      file_(std::move(file)), line_(line), message_(std::move(message)) {}

std::vector<ShaderDefine> feature_defines(const scenes::FeatureSet& features) {
  std::vector<ShaderDefine> out;
  for (std::string n : features.names()) {
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::toupper(c); });
    out.push_back({"GIQ_" + n, "1"});
  }
  return out;
}

std::optional<std::string> shader_source(std::string_view path) {
  if (const char* dir = std::getenv("GIQ_SHADER_DIR")) {
    std::ifstream f(std::filesystem::path(dir) / std::string(path), std::ios::binary);
    if (f) return std::string(std::istreambuf_iterator<char>(f), {});
  }
  for (size_t i = 0; i < detail::kEmbeddedShaderCount; ++i)
    if (path == detail::kEmbeddedShaders[i].path) return std::string(detail::kEmbeddedShaders[i].text);
  return std::nullopt;
}

namespace {

EShLanguage stage_of(const std::string& name) {
  const auto ext = std::filesystem::path(name).extension().string();
  if (ext == ".vert") return EShLangVertex;
  if (ext == ".frag") return EShLangFragment;
  if (ext == ".geom") return EShLangGeometry;
  if (ext == ".comp") return EShLangCompute;
  throw std::invalid_argument("shader '" + name + "': unknown stage (expected .comp, .vert, .frag or .geom)");
}

// Resolves #include against the including file's folder, then the shader root.
class Includer : public glslang::TShader::Includer {
 public:
  IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
    const std::filesystem::path dir = std::filesystem::path(includer).parent_path();
    const std::string rel = (dir / header).lexically_normal().generic_string();
    if (auto s = shader_source(rel)) return make(rel, std::move(*s));
    return includeSystem(header, includer, 0);
  }
  IncludeResult* includeSystem(const char* header, const char*, size_t) override {
    const std::string rel = std::filesystem::path(header).lexically_normal().generic_string();
    if (auto s = shader_source(rel)) return make(rel, std::move(*s));
    return nullptr;  // glslang reports "could not process include directive" at the line
  }
  void releaseInclude(IncludeResult* r) override {
    if (!r) return;
    delete static_cast<std::string*>(r->userData);
    delete r;
  }

 private:
  static IncludeResult* make(const std::string& name, std::string text) {
    auto* owned = new std::string(std::move(text));
    return new IncludeResult(name, owned->data(), owned->size(), owned);
  }
};

void initialise_glslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

constexpr EShMessages kMessages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules);

void configure(glslang::TShader& shader, EShLanguage stage, const char* const* text, const char* const* name,
               const std::string& preamble) {
  shader.setStringsWithLengthsAndNames(text, nullptr, name, 1);
  shader.setPreamble(preamble.c_str());
  shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
}

// glslang logs "ERROR: <file>:<line>: <message>"; the first such line becomes the error.
[[noreturn]] void throw_log(const std::string& name, const std::string& log) {
  static const std::regex re(R"(ERROR: (.*?):(\d+): (.*))");
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, re)) throw ShaderError(m[1], std::stoi(m[2]), m[3], log);
  }
  throw ShaderError(name, 0, log.empty() ? "compilation failed" : log, log);
}

}  // namespace

ShaderCompiler::ShaderCompiler(std::filesystem::path cache_dir) : cache_dir_(std::move(cache_dir)) {}

std::filesystem::path ShaderCompiler::default_cache_dir() {
  if (const char* d = std::getenv("GIQ_SHADER_CACHE")) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::filesystem::path(d) / "giq" / "spirv";
  if (const char* d = std::getenv("HOME"); d && *d) return std::filesystem::path(d) / ".cache" / "giq" / "spirv";
  return {};
}

std::vector<uint32_t> ShaderCompiler::compile(const std::string& path, const std::vector<ShaderDefine>& defines) {
  auto src = shader_source(path);
  if (!src) throw std::invalid_argument("no shader '" + path + "' in this build");
  return compile_source(path, *src, defines);
}

std::vector<uint32_t> ShaderCompiler::compile_source(const std::string& name, const std::string& source,
                                                     const std::vector<ShaderDefine>& defines) {
  initialise_glslang();
  const EShLanguage stage = stage_of(name);
  std::string preamble;
  for (const auto& d : defines) preamble += "#define " + d.name + " " + d.value + "\n";
  const char* text = source.c_str();
  const char* cname = name.c_str();
  const TBuiltInResource* resources = GetDefaultResources();

  // The cache key is the preprocessed text: every include and define is in it.
  Includer includer;
  std::string preprocessed;
  {
    glslang::TShader pre(stage);
    configure(pre, stage, &text, &cname, preamble);
    if (!pre.preprocess(resources, 100, ENoProfile, false, false, kMessages, &preprocessed, includer))
      throw_log(name, pre.getInfoLog());
  }
  Hasher h;
  h.add("glslang-12 vulkan1.3 spirv1.5 ").add(std::to_string(int(stage))).add("\n").add(preamble).add(preprocessed);
  const std::filesystem::path cached = cache_dir_.empty() ? std::filesystem::path() : cache_dir_ / (h.hex() + ".spv");
  if (!cached.empty()) {
    std::ifstream f(cached, std::ios::binary);
    if (f) {
      std::string bytes((std::istreambuf_iterator<char>(f)), {});
      if (bytes.size() >= 20 && bytes.size() % 4 == 0) {
        std::vector<uint32_t> spirv(bytes.size() / 4);
        std::memcpy(spirv.data(), bytes.data(), bytes.size());
        if (spirv[0] == 0x07230203u) {  // SPIR-V magic number
          ++cache_hits_;
          return spirv;
        }
      }
    }
  }

  glslang::TShader shader(stage);
  configure(shader, stage, &text, &cname, preamble);
  if (!shader.parse(resources, 100, false, kMessages, includer)) throw_log(name, shader.getInfoLog());
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(kMessages)) throw_log(name, program.getInfoLog());
  std::vector<uint32_t> spirv;
  glslang::SpvOptions options;
  options.generateDebugInfo = false;
  options.disableOptimizer = false;
  glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &options);
  ++compilations_;

  if (!cached.empty()) {
    // A cache that cannot be written (read-only home, full disk) only costs a recompile.
    try {
      std::filesystem::create_directories(cache_dir_);
      write_file_atomically(cached, std::string_view(reinterpret_cast<const char*>(spirv.data()), spirv.size() * 4));
    } catch (const std::exception&) {
    }
  }
  return spirv;
}

}  // namespace giq::realtime
