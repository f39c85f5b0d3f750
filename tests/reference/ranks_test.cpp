// `mpirun -n R giq reference` end to end (GIQ_WITH_MPI; distributed_render.h): 1, 2 and 3
// ranks write the single process's files byte for byte, for a sequence too; a rank killed
// mid-render and a resume with another number of ranks give the same bytes; what cannot be
// split across ranks exits 2 with one line; `giq golden update --launcher` writes the same
// goldens. The machine has 2 cores, so the ranks are oversubscribed.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "giq/reference/part.h"
#include "support/scratch.h"
#include "support/subprocess.h"

namespace fs = std::filesystem;
using giq::test::Outcome;
using giq::test::run_captured;
using giq::test::shell_quote;
using giq::test::slurp;

namespace {

const fs::path& scratch() {
  static const giq::test::ScratchDir s("ranks");
  return s.path;
}
std::string path(const std::string& name) { return shell_quote((scratch() / name).string()); }

// Open MPI refuses root unless told twice (CI runs as root); containers may forbid the
// cross-memory attach its shared-memory transport tries first.
// As words (no quoting), so that giq golden update --launcher can take it too.
std::string launcher(int ranks) {
  return std::string("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ") +
         "OMPI_MCA_btl_vader_single_copy_mechanism=none " + GIQ_MPIEXEC + " --oversubscribe -n " + std::to_string(ranks);
}
Outcome giq(const std::string& args, int ranks = 0) {
  return run_captured((ranks > 0 ? launcher(ranks) + " " : std::string()) + shell_quote(GIQ_BINARY) + " " + args,
                      scratch() / "log");
}
std::string scene(const std::string& name) { return shell_quote(std::string(GIQ_SCENES_DIR) + "/" + name); }

// Lines giq wrote (mpirun adds banners of its own).
int giq_lines(const std::string& err) {
  int n = 0;
  for (size_t at = 0; (at = err.find("giq: ", at)) != std::string::npos; ++at) ++n;
  return n;
}

TEST(ReferenceRanks, OneTwoAndThreeRanksWriteTheSingleProcessFiles) {
  // Two frames of the moving light at 150 x 70: 3 x 2 units a frame, so 12 units for 2 or 3
  // ranks, with partial units at the right and bottom edges.
  const std::string args = "reference --scene " + scene("movinglight.gltf") + " --frames 2:3 --width 150 --height 70 --spp 8 ";
  ASSERT_EQ(giq(args + "--out " + path("single/f#.exr")).exit_code, 0);
  for (int n : {1, 2, 3}) {
    const std::string dir = "ranks" + std::to_string(n);
    const Outcome r = giq(args + "--out " + path(dir + "/f#.exr"), n);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"f2.exr", "f3.exr"}) {
      const std::string single = slurp(scratch() / "single" / f);
      ASSERT_FALSE(single.empty());
      EXPECT_EQ(slurp(scratch() / dir / f), single) << n << " ranks, " << f;
    }
  }
}

// The pids of the ranks rendering into `out`: processes whose command line names it and does
// not start with the launcher.
std::vector<pid_t> ranks_writing(const std::string& out) {
  std::vector<pid_t> pids;
  for (const fs::directory_entry& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = slurp(e.path() / "cmdline");
    for (char& c : cmdline) c = c == '\0' ? ' ' : c;
    if (cmdline.find(out) != std::string::npos && cmdline.find(" reference ") != std::string::npos &&
        cmdline.find("mpirun") == std::string::npos && cmdline.find("mpiexec") == std::string::npos &&
        cmdline.find("orterun") == std::string::npos && cmdline.rfind("sh ", 0) != 0 && cmdline.rfind("/bin/sh", 0) != 0)
      pids.push_back(pid_t(std::stol(name)));
  }
  return pids;
}

TEST(ReferenceRanks, AKilledRankCostsOnlyItsCheckpointInterval) {
  const std::string args = "reference --scene " + scene("cornell.gltf") + " --width 192 --height 128 --spp 256 ";
  ASSERT_EQ(giq(args + "--out " + path("whole.exr")).exit_code, 0);
  const fs::path out = scratch() / "killed.exr", checkpoint = scratch() / "killed.exr.ranks.checkpoint",
                 status = scratch() / "killed.status";
  // Three ranks in the background, checkpointing every 0.2 s.
  const std::string cmd = "(" + launcher(3) + " " + shell_quote(GIQ_BINARY) + " " + args + "--checkpoint-interval 0.2 --out " +
                          shell_quote(out.string()) + " >/dev/null 2>&1; echo $? >" + shell_quote(status.string()) + ") &";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(checkpoint) && !fs::exists(status) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(checkpoint)) << "no checkpoint before the render ended";
  const std::vector<pid_t> pids = ranks_writing(out.string());
  ASSERT_EQ(pids.size(), 3u);
  ASSERT_EQ(::kill(pids.back(), SIGKILL), 0);
  while (!fs::exists(status) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(status));
  EXPECT_NE(std::stoi(slurp(status)), 0);
  ASSERT_FALSE(fs::exists(out)) << "the render ended before the kill";
  // The checkpoint holds rendered samples.
  const giq::reference::Part saved = giq::reference::read_part(checkpoint, giq::reference::PartUse::Checkpoint);
  uint64_t samples = 0;
  for (const auto& f : saved.frames)
    for (const auto& p : f.pixels) samples += p.samples;
  EXPECT_GT(samples, 0u);
  // Resumed with two ranks: the same bytes as one process, and the checkpoint is gone.
  const Outcome r = giq(args + "--resume --out " + shell_quote(out.string()), 2);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(out), slurp(scratch() / "whole.exr"));
  EXPECT_FALSE(fs::exists(checkpoint));
}

TEST(ReferenceRanks, WhatCannotBeSplitExitsTwoWithOneLine) {
  const std::string args = "reference --scene " + scene("cornell.gltf") + " --width 64 --height 32 ";
  for (const std::string& bad : {std::string("--rel-error 0.1"), std::string("--spp 4 --time 3"),
                                 std::string("--spp 4 --shard 1/2"), std::string("--spp 4 --record-time")}) {
    const Outcome r = giq(args + bad + " --out " + path("bad.exr"), 2);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_EQ(giq_lines(r.err), 1) << bad << ": " << r.err;
  }
  // A checkpoint of another render (another spp) is refused, not mixed in.
  giq::reference::Part other;
  other.identity = "another render";
  other.settings.width = 64, other.settings.height = 32;
  other.spp = 4, other.shard = {1, 1};
  giq::reference::write_part(scratch() / "mixed.exr.ranks.checkpoint", other);
  const Outcome r = giq(args + "--spp 8 --resume --out " + path("mixed.exr"), 2);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(giq_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("mixed.exr.ranks.checkpoint"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("checkpoint of another render"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(scratch() / "mixed.exr"));
}

TEST(ReferenceRanks, GoldenUpdateWithALauncherWritesTheSameGoldens) {
  for (const std::string dir : {"plain", "launched"}) {
    fs::create_directories(scratch() / dir);
    std::ofstream(scratch() / dir / "gate.json")
        << R"({"version": 1, "defaults": {"scene": ")" << GIQ_SCENES_DIR
        << R"(/cornell.gltf", "resolution": [80, 40], "golden": {"spp": 16, "seed": 3}},
              "cases": [{"name": "c", "technique": "direct", "bounds": {"relmse": 1}}]})";
  }
  const auto update = [](const std::string& dir, const std::string& extra) {
    return run_captured("cd " + path(dir) + " && " + shell_quote(GIQ_BINARY) + " golden update --config gate.json" + extra,
                        scratch() / "log");
  };
  const Outcome plain = update("plain", "");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const Outcome launched = update("launched", " --launcher " + shell_quote(launcher(3)));
  ASSERT_EQ(launched.exit_code, 0) << launched.out << launched.err;
  int frames = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(scratch() / "plain")) {
    if (e.path().extension() != ".exr") continue;
    ++frames;
    const fs::path twin = scratch() / "launched" / e.path().lexically_relative(scratch() / "plain");
    EXPECT_EQ(slurp(twin), slurp(e.path())) << twin;
  }
  EXPECT_EQ(frames, 1);
}

}  // namespace
