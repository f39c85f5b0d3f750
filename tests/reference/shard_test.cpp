// End to end: `giq reference --shard K/N` and `giq reference merge`. However a render is cut
// into shards and whatever order the parts are given in, the merge writes the single-process
// file byte for byte, for one frame and for a sequence; incomplete or mixed part sets and bad
// --shard values exit 2 with one line naming what is wrong.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/scratch.h"
#include "support/subprocess.h"

namespace fs = std::filesystem;
using giq::test::Outcome;
using giq::test::run_captured;
using giq::test::shell_quote;
using giq::test::slurp;

namespace {

const fs::path& scratch() {
  static const giq::test::ScratchDir s("shard");
  return s.path;
}

Outcome giq(const std::string& args) { return run_captured(shell_quote(GIQ_BINARY) + " " + args, scratch() / "log"); }

std::string cornell(const std::string& extra) {
  return "reference --scene " + shell_quote(std::string(GIQ_SCENES_DIR) + "/cornell.gltf") +
         " --spp 8 --width 150 --height 70 " + extra;
}

std::string path(const std::string& name) { return shell_quote((scratch() / name).string()); }

// The parts of cornell() cut into n shards, written as <stem>.<k>.part; their paths in the order
// given by `order` (1-based shard numbers).
std::string shards(const std::string& stem, int n, const std::vector<int>& order, const std::string& extra = "") {
  std::string parts;
  for (int k = 1; k <= n; ++k) {
    const Outcome r = giq(cornell(extra + " --shard " + std::to_string(k) + "/" + std::to_string(n) + " --out " +
                                  path(stem + "." + std::to_string(k) + ".part")));
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  for (int k : order) parts += " " + path(stem + "." + std::to_string(k) + ".part");
  return parts;
}

TEST(ReferenceShards, MergeIntoTheSingleProcessFileBitForBit) {
  ASSERT_EQ(giq(cornell("--out " + path("single.exr"))).exit_code, 0);
  // 150 x 70 pixels are 3 x 2 units of 64 x 64: four shards get 2, 2, 1 and 1.
  const Outcome m = giq("reference merge" + shards("four", 4, {3, 1, 4, 2}) + " --out " + path("merged.exr"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(slurp(scratch() / "merged.exr"), slurp(scratch() / "single.exr"));
  // More shards than units: the shards without a unit write empty parts, and the merge is the same.
  ASSERT_EQ(giq("reference merge" + shards("ten", 10, {10, 9, 8, 7, 6, 5, 4, 3, 2, 1}) + " --out " + path("ten.exr")).exit_code, 0);
  EXPECT_EQ(slurp(scratch() / "ten.exr"), slurp(scratch() / "single.exr"));
  // --half on the merge gives what --half on the single process gives.
  ASSERT_EQ(giq(cornell("--half --out " + path("single_half.exr"))).exit_code, 0);
  ASSERT_EQ(giq("reference merge --half" + shards("four", 4, {1, 2, 3, 4}) + " --out " + path("half.exr")).exit_code, 0);
  EXPECT_EQ(slurp(scratch() / "half.exr"), slurp(scratch() / "single_half.exr"));
}

TEST(ReferenceShards, MergeASequenceFrameByFrame) {
  // Three frames of the moving light: the light and so every frame's image differ, and each
  // frame's units are spread over the shards.
  const std::string scene = shell_quote(std::string(GIQ_SCENES_DIR) + "/movinglight.gltf");
  const std::string render = "reference --scene " + scene + " --spp 4 --width 96 --height 64 --frames 10:12 ";
  ASSERT_EQ(giq(render + "--out " + path("seq_single_##.exr")).exit_code, 0);
  std::string parts;
  for (int k = 1; k <= 5; ++k) {
    const Outcome r = giq(render + "--shard " + std::to_string(k) + "/5 --out " + path("seq." + std::to_string(k) + ".part"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    parts += " " + path("seq." + std::to_string(k) + ".part");
  }
  const Outcome m = giq("reference merge" + parts + " --out " + path("seq_merged_##.exr"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  for (int f = 10; f <= 12; ++f) {
    const std::string single = slurp(scratch() / ("seq_single_" + std::to_string(f) + ".exr"));
    ASSERT_FALSE(single.empty()) << f;
    EXPECT_EQ(slurp(scratch() / ("seq_merged_" + std::to_string(f) + ".exr")), single) << "frame " << f;
  }
}

// One line on stderr, exit 2, and no output file.
void expect_refused(const std::string& args, const std::string& message) {
  fs::remove(scratch() / "refused.exr");
  const Outcome r = giq(args);
  EXPECT_EQ(r.exit_code, 2) << args;
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(scratch() / "refused.exr"));
}

TEST(ReferenceShards, MergeRefusesIncompleteDuplicatedOrMixedParts) {
  const std::string p1 = path("mix.1.part"), p2 = path("mix.2.part"), p3 = path("mix.3.part");
  shards("mix", 3, {});
  const std::string out = " --out " + path("refused.exr");
  expect_refused("reference merge " + p1 + " " + p3 + out, "shard 2 of 3 is missing");
  expect_refused("reference merge " + p1 + out, "shards 2, 3 of 3 are missing");
  expect_refused("reference merge " + p1 + " " + p2 + " " + p2 + " " + p3 + out, "shard 2/3 is given twice");
  // Another seed is another render; so is another shard count.
  ASSERT_EQ(giq(cornell("--seed 9 --shard 3/3 --out " + path("seed.part"))).exit_code, 0);
  expect_refused("reference merge " + p1 + " " + p2 + " " + path("seed.part") + out, "seed.part: part: belongs to another render");
  ASSERT_EQ(giq(cornell("--shard 3/4 --out " + path("four3.part"))).exit_code, 0);
  expect_refused("reference merge " + p1 + " " + p2 + " " + path("four3.part") + out, "is shard 3 of 4");
  // A damaged part, and a file that is no part at all.
  std::string bytes = slurp(scratch() / "mix.2.part");
  bytes[bytes.size() / 2] ^= 0x20;
  std::ofstream(scratch() / "bad.part", std::ios::binary) << bytes;
  expect_refused("reference merge " + p1 + " " + path("bad.part") + " " + p3 + out, "checksum mismatch");
  expect_refused("reference merge " + p1 + " " + p2 + " " + shell_quote(std::string(GIQ_SCENES_DIR) + "/cornell.gltf") + out,
                 "not a part of a sharded reference render");
}

TEST(ReferenceShards, BadShardsAreRefused) {
  for (const char* bad : {"0/3", "4/3", "2", "a/b", "1/0", "-1/2", "1/2/3"})
    expect_refused(cornell(std::string("--shard ") + bad + " --out " + path("refused.exr")), "expected K/N");
  expect_refused("reference --scene " + shell_quote(std::string(GIQ_SCENES_DIR) + "/cornell.gltf") +
                     " --rel-error 0.1 --shard 1/2 --out " + path("refused.exr"),
                 "shards stop at a sample count");
}

}  // namespace
