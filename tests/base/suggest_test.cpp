// "Did you mean": a typo finds its name (one edit in a short name, a swap of neighbours, a
// case slip, up to a third of a long name), and a different word finds nothing.

#include <gtest/gtest.h>

#include "giq/base/suggest.h"

using giq::did_you_mean;
using giq::nearest_name;

TEST(Suggest, TyposFindTheirNameAndOtherWordsNothing) {
  const std::vector<std::string> techniques = {"direct", "pt", "rsm", "lpv", "vct", "ddgi"};
  EXPECT_EQ(nearest_name("dirct", techniques), "direct");    // a deletion
  EXPECT_EQ(nearest_name("driect", techniques), "direct");   // neighbours swapped
  EXPECT_EQ(nearest_name("DIRECT ", techniques), "direct");  // case, and a stray blank
  EXPECT_EQ(nearest_name("ddig", techniques), "ddgi");
  EXPECT_EQ(nearest_name("gi1", techniques), "");            // not a typo of any of them
  EXPECT_EQ(nearest_name("direct", techniques), "");         // already a name: nothing to suggest
  EXPECT_EQ(nearest_name("", techniques), "");
  const std::vector<std::string> options = {"--scene", "--spp", "--seed", "--tonemap", "--test-layer"};
  EXPECT_EQ(nearest_name("--tonemp", options), "--tonemap");
  EXPECT_EQ(nearest_name("--testlayer", options), "--test-layer");
  EXPECT_EQ(nearest_name("--width", options), "");
  // The nearest of two candidates wins: one edit from "--spp", two from "--seed".
  EXPECT_EQ(nearest_name("--sp", options), "--spp");
  EXPECT_EQ(did_you_mean("sacrsty", {"nave", "aisle", "sacristy"}), "; did you mean 'sacristy'?");
  EXPECT_EQ(did_you_mean("kitchen", {"nave", "aisle", "sacristy"}), "");
}
