#include "giq/base/hash.h"

#include <gtest/gtest.h>

// Published FNV-1a 64-bit test vectors (Fowler/Noll/Vo reference test suite).
TEST(Hasher, MatchesFnv1aTestVectors) {
  EXPECT_EQ(giq::Hasher().value(), 0xcbf29ce484222325ull);
  EXPECT_EQ(giq::Hasher().add("a").value(), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(giq::Hasher().add("foobar").value(), 0x85944171f73967e8ull);
  EXPECT_EQ(giq::Hasher().add("foobar").hex(), "85944171f73967e8");
}

TEST(Hasher, IncrementalEqualsWhole) {
  EXPECT_EQ(giq::Hasher().add("foo").add("bar").value(), giq::Hasher().add("foobar").value());
}
