#include "giq/image/image.h"

#include <gtest/gtest.h>

#include "giq/base/error.h"

using giq::image::Image;

TEST(Image, ChannelsKeepOrderAndPointers) {
  Image img(3, 2);
  float* r = img.add_channel("R", 1.0f);
  img.add_channel("G", 2.0f);
  img.add_channel("B", 3.0f);
  for (int i = 0; i < 20; ++i) img.add_channel("extra" + std::to_string(i));
  EXPECT_EQ(r, img.channel("R"));  // adding channels never moves an existing plane
  EXPECT_EQ(img.add_channel("G", 9.0f), img.channel("G"));
  EXPECT_EQ(img.at("G", 2, 1), 2.0f);
  EXPECT_EQ(img.channel_names()[0], "R");
  EXPECT_EQ(img.channel_names()[2], "B");
  img.remove_channel("extra3");
  EXPECT_FALSE(img.has_channel("extra3"));
  EXPECT_EQ(img.channel_names().size(), 22u);
}

TEST(Image, MissingChannelNamesThePresentOnes) {
  Image img(1, 1);
  img.add_channel("Z");
  try {
    img.channel("objectId");
    FAIL() << "expected InputError";
  } catch (const giq::InputError& e) {
    EXPECT_EQ(e.field(), "objectId");
    EXPECT_NE(std::string(e.what()).find("Z"), std::string::npos);
  }
}

TEST(Image, Layers) {
  Image img(1, 1);
  for (const char* c : {"R", "G", "B", "indirect.R", "indirect.G", "indirect.B", "N.X", "N.Y", "N.Z", "Z",
                        "variance.R", "variance.G"})
    img.add_channel(c);
  EXPECT_EQ(img.layer_channels("beauty")[1], "G");
  EXPECT_EQ(img.layer_channels("indirect")[2], "indirect.B");
  EXPECT_EQ(img.layer_channels("N")[0], "N.X");
  EXPECT_FALSE(img.has_layer("variance"));  // variance.B is missing
  const std::vector<std::string> expected{"", "indirect", "N"};
  EXPECT_EQ(img.layers(), expected);
}
