#include "giq/base/staged_folder.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "support/scratch.h"

namespace fs = std::filesystem;

namespace {

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
  const fs::path d = giq::test::fresh_dir("staged_publish");
  previous_run(d);
  const fs::path outside = d.parent_path() / (d.filename().string() + "_outside.txt");
  giq::write_file_atomically(outside, "not giq's to remove");
  {
    giq::StagedFolder folder(d, "manifest.json");
    EXPECT_EQ(folder.staging().parent_path(), d);
    giq::write_file_atomically(folder.staging() / "a.exr", "new a");
    giq::write_file_atomically(folder.staging() / "b.png", "new b");
    giq::write_file_atomically(folder.staging() / "manifest.json", "new manifest");
    // Nothing of the new run is visible before publishing.
    EXPECT_EQ(giq::test::slurp(d / "manifest.json"), "old manifest");
    EXPECT_EQ(giq::test::slurp(d / "a.exr"), "old a");
    // A hostile previous manifest cannot make publish remove anything outside the folder.
    folder.publish({"a.exr", "old_only.png", "../" + outside.filename().string(), "/etc/hostname", ".."});
  }
  EXPECT_EQ(listing(d), (std::set<std::string>{"manifest.json", "a.exr", "b.png", "notes.txt"}));
  EXPECT_EQ(giq::test::slurp(d / "manifest.json"), "new manifest");
  EXPECT_EQ(giq::test::slurp(d / "a.exr"), "new a");
  EXPECT_EQ(giq::test::slurp(d / "notes.txt"), "the user's");
  EXPECT_TRUE(fs::exists(outside));
  fs::remove(outside);
}

TEST(StagedFolder, ARunThatFailsLeavesThePreviousRunUntouched) {
  const fs::path d = giq::test::fresh_dir("staged_fails");
  previous_run(d);
  const std::set<std::string> before = listing(d);
  try {
    giq::StagedFolder folder(d, "manifest.json");
    giq::write_file_atomically(folder.staging() / "a.exr", "new a");
    throw giq::InputError("x", "", "disk full halfway");
  } catch (const giq::InputError&) {
  }
  EXPECT_EQ(listing(d), before);
  EXPECT_EQ(giq::test::slurp(d / "a.exr"), "old a");
  EXPECT_EQ(giq::test::slurp(d / "manifest.json"), "old manifest");
}

TEST(StagedFolder, ASecondWriterIsRefusedUntilTheFirstEnds) {
  const fs::path d = giq::test::fresh_dir("staged_lock");
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
  const fs::path d = giq::test::fresh_dir("staged_killed");
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
  const fs::path d = giq::test::fresh_dir("staged_file");
  giq::write_file_atomically(d / "out", "a file");
  EXPECT_THROW(giq::StagedFolder(d / "out", "manifest.json"), giq::InputError);
  EXPECT_EQ(giq::test::slurp(d / "out"), "a file");
}
