// `giq reference merge`: joins the N part files of a sharded reference render (giq reference
// --shard K/N) into the EXR files a single process would have written, bit for bit
// (reference/part.h, docs/reference.md "Shards").

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "command.h"
#include "output_guard.h"
#include "reference_output.h"
#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/reference/part.h"
#include "giq/reference/reference_exr.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
namespace ref = giq::reference;

struct MergeArgs {
  std::vector<std::string> parts;
  std::string out;
  bool half = false;
};

int run_merge(const MergeArgs& a) {
  std::string ext = fs::path(a.out).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".exr") throw InputError(a.out, "--out", "the reference is written as OpenEXR; expected a file name ending in .exr");
  std::vector<ref::Part> parts;
  for (const std::string& file : a.parts) parts.push_back(ref::read_part(file));
  const std::vector<ref::MergedFrame> frames = ref::merge_parts(parts, a.parts);
  const ref::Part& p = parts.front();
  const bool several = frames.size() > 1;
  const std::vector<fs::path> inputs(a.parts.begin(), a.parts.end());
  for (const ref::MergedFrame& m : frames) check_output_file(frame_path(a.out, m.frame, several), inputs, "--out");
  for (const ref::MergedFrame& m : frames) {
    // The metadata `giq reference` gives the same render (no render time: it is not recorded
    // by default, and a merged render has none of its own).
    ref::ReferenceMetadata meta;
    meta.scene = p.scene;
    meta.scene_hash = p.scene_hash;
    meta.view = p.view;
    meta.camera = m.camera;
    meta.camera_given = p.camera_given;
    meta.frame = m.frame;
    const fs::path out = frame_path(a.out, m.frame, several);
    if (out.has_parent_path()) fs::create_directories(out.parent_path());
    const image::Image img = ref::reference_image(m.film, p.settings, meta);
    image::write_exr(img, out, exr_options(img, a.half));
    std::printf("reference %s: %dx%d, frame %d, %u spp, merged from %zu parts\n", out.string().c_str(), m.film.width,
                m.film.height, m.frame, p.spp, parts.size());
  }
  return 0;
}

}  // namespace

CLI::App* add_reference_merge_command(CLI::App& reference, int& exit_code) {
  auto a = std::make_shared<MergeArgs>();
  CLI::App* cmd = reference.add_subcommand(
      "merge", "Join the N part files of a sharded render (giq reference --shard K/N) into its reference EXR files");
  cmd->add_option("parts", a->parts, "The part files, all N of them, in any order")->required();
  cmd->add_option("--out", a->out, "Output EXR path ('#' runs become the frame number for several frames)")->required();
  cmd->add_flag("--half", a->half, "Store the colour layers as float16, as giq reference --half does");
  cmd->footer(
      "Example: eight processes, then the merge (the same bits as one process with --spp 1024):\n"
      "  for k in 1 2 3 4 5 6 7 8; do giq reference --scene S --spp 1024 --shard $k/8 --out parts/$k.part & done; wait\n"
      "  giq reference merge parts/*.part --out ref.exr");
  cmd->callback([a, &exit_code] { exit_code = run_merge(*a); });
  return cmd;
}

}  // namespace giq::cli
