#include "giq/base/atomic_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include "support/scratch.h"

namespace fs = std::filesystem;

TEST(AtomicFile, WritesContent) {
  fs::path d = giq::test::fresh_dir("atomic_writes");
  giq::write_file_atomically(d / "a.txt", "hello");
  EXPECT_EQ(giq::test::slurp(d / "a.txt"), "hello");
  // Exactly one file: no temporary left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 1);
}

TEST(AtomicFile, ThrowingWriterLeavesOldFileAndNoTemporary) {
  fs::path d = giq::test::fresh_dir("atomic_throws");
  giq::write_file_atomically(d / "a.txt", "old");
  EXPECT_THROW(giq::write_atomically(d / "a.txt",
                                     [](const fs::path& tmp) {
                                       std::ofstream(tmp) << "half of the new conte";
                                       throw std::runtime_error("writer died");
                                     }),
               std::runtime_error);
  EXPECT_EQ(giq::test::slurp(d / "a.txt"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 1);
}

TEST(AtomicFile, ThrowingWriterCreatesNothing) {
  fs::path d = giq::test::fresh_dir("atomic_nothing");
  EXPECT_THROW(giq::write_atomically(d / "new.exr",
                                     [](const fs::path& tmp) {
                                       std::ofstream(tmp) << "partial";
                                       throw std::runtime_error("interrupted");
                                     }),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(d / "new.exr"));
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(AtomicFile, CreatesParentDirectories) {
  fs::path d = giq::test::fresh_dir("atomic_parents");
  giq::write_file_atomically(d / "x" / "y" / "z.txt", "deep");
  EXPECT_EQ(giq::test::slurp(d / "x" / "y" / "z.txt"), "deep");
}
