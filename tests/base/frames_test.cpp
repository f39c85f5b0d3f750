#include "giq/base/frames.h"

#include <gtest/gtest.h>

namespace giq {
namespace {

TEST(Frames, FileNamesArePaddedToFourDigits) {
  EXPECT_EQ(frame_file(7), "frame_0007.exr");
  EXPECT_EQ(frame_file(12345), "frame_12345.exr");
  EXPECT_EQ(frame_range(2, 9), "2:9");
}

TEST(Frames, RangesAreTwoNonNegativeIntegersInOrder) {
  EXPECT_EQ(parse_frame_range("0:59"), (std::pair{0, 59}));
  EXPECT_EQ(parse_frame_range("3:3"), (std::pair{3, 3}));
  for (const char* bad : {"", ":", "1", "5:2", "-1:3", "1:2x", " 1:2", "1:2:3", "a:b", "1.5:2", "99999999999:1"})
    EXPECT_FALSE(parse_frame_range(bad)) << bad;
}

}  // namespace
}  // namespace giq
