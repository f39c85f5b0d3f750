#include "giq/base/atomic_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("giq_atomic_" + name + "_" + std::to_string(::getpid()));
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

}  // namespace

TEST(AtomicFile, WritesContent) {
  fs::path d = fresh_dir("writes");
  giq::write_file_atomically(d / "a.txt", "hello");
  EXPECT_EQ(slurp(d / "a.txt"), "hello");
  // Exactly one file: no temporary left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 1);
}

TEST(AtomicFile, ThrowingWriterLeavesOldFileAndNoTemporary) {
  fs::path d = fresh_dir("throws");
  giq::write_file_atomically(d / "a.txt", "old");
  EXPECT_THROW(giq::write_atomically(d / "a.txt",
                                     [](const fs::path& tmp) {
                                       std::ofstream(tmp) << "half of the new conte";
                                       throw std::runtime_error("writer died");
                                     }),
               std::runtime_error);
  EXPECT_EQ(slurp(d / "a.txt"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 1);
}

TEST(AtomicFile, ThrowingWriterCreatesNothing) {
  fs::path d = fresh_dir("nothing");
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
  fs::path d = fresh_dir("parents");
  giq::write_file_atomically(d / "x" / "y" / "z.txt", "deep");
  EXPECT_EQ(slurp(d / "x" / "y" / "z.txt"), "deep");
}
