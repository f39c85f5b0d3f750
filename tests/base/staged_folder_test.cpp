#include "giq/base/staged_folder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <set>
#include <sstream>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("giq_staged_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::set<std::string> listing(const fs::path& d) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(d)) names.insert(e.path().filename().string());
  return names;
}

// A previous run: manifest naming a.exr and old_only.png, plus a file of the user's.
void previous_run(const fs::path& d) {
  giq::write_file_atomically(d / "manifest.json", "old manifest");
  giq::write_file_atomically(d / "a.exr", "old a");
  giq::write_file_atomically(d / "old_only.png", "old only");
  giq::write_file_atomically(d / "notes.txt", "the user's");
}

}  // namespace

TEST(StagedFolder, PublishReplacesThePreviousRunAsAWhole) {
  const fs::path d = fresh_dir("publish");
  previous_run(d);
  giq::write_file_atomically(d.parent_path() / "outside.txt", "not giq's to remove");
  {
    giq::StagedFolder folder(d, "manifest.json");
    EXPECT_EQ(folder.staging().parent_path(), d);
    giq::write_file_atomically(folder.staging() / "a.exr", "new a");
    giq::write_file_atomically(folder.staging() / "b.png", "new b");
    giq::write_file_atomically(folder.staging() / "manifest.json", "new manifest");
    // Nothing of the new run is visible before publishing.
    EXPECT_EQ(slurp(d / "manifest.json"), "old manifest");
    EXPECT_EQ(slurp(d / "a.exr"), "old a");
    // A hostile previous manifest cannot make publish remove anything outside the folder.
    folder.publish({"a.exr", "old_only.png", "../outside.txt", "/etc/hostname", ".."});
  }
  EXPECT_EQ(listing(d), (std::set<std::string>{"manifest.json", "a.exr", "b.png", "notes.txt"}));
  EXPECT_EQ(slurp(d / "manifest.json"), "new manifest");
  EXPECT_EQ(slurp(d / "a.exr"), "new a");
  EXPECT_EQ(slurp(d / "notes.txt"), "the user's");
  EXPECT_TRUE(fs::exists(d.parent_path() / "outside.txt"));
  fs::remove(d.parent_path() / "outside.txt");
}

TEST(StagedFolder, ARunThatFailsLeavesThePreviousRunUntouched) {
  const fs::path d = fresh_dir("fails");
  previous_run(d);
  const std::set<std::string> before = listing(d);
  try {
    giq::StagedFolder folder(d, "manifest.json");
    giq::write_file_atomically(folder.staging() / "a.exr", "new a");
    throw giq::InputError("x", "", "disk full halfway");
  } catch (const giq::InputError&) {
  }
  EXPECT_EQ(listing(d), before);
  EXPECT_EQ(slurp(d / "a.exr"), "old a");
  EXPECT_EQ(slurp(d / "manifest.json"), "old manifest");
}

TEST(StagedFolder, ASecondWriterIsRefusedUntilTheFirstEnds) {
  const fs::path d = fresh_dir("lock");
  {
    giq::StagedFolder first(d, "manifest.json");
    try {
      giq::StagedFolder second(d, "manifest.json");
      FAIL() << "a second writer was let in";
    } catch (const giq::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("another giq process is writing to this folder"), std::string::npos)
          << e.what();
    }
    // The refused writer did not disturb the first one's staging.
    EXPECT_TRUE(fs::is_directory(first.staging()));
  }
  EXPECT_NO_THROW(giq::StagedFolder(d, "manifest.json"));
}

TEST(StagedFolder, StagingLeftByAKilledRunIsRemoved) {
  const fs::path d = fresh_dir("killed");
  fs::create_directories(d / ".giq-staging-999999");
  giq::write_file_atomically(d / ".giq-staging-999999" / "a.exr", "half");
  {
    giq::StagedFolder folder(d, "manifest.json");
    giq::write_file_atomically(folder.staging() / "manifest.json", "m");
    folder.publish({});
  }
  EXPECT_EQ(listing(d), (std::set<std::string>{"manifest.json"}));
}

TEST(StagedFolder, AFileWhereTheFolderShouldBeIsAnInputError) {
  const fs::path d = fresh_dir("file");
  giq::write_file_atomically(d / "out", "a file");
  EXPECT_THROW(giq::StagedFolder(d / "out", "manifest.json"), giq::InputError);
  EXPECT_EQ(slurp(d / "out"), "a file");
}
