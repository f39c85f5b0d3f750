#include "giq/base/error.h"

#include <gtest/gtest.h>

TEST(InputError, NamesFileFieldAndMessageOnOneLine) {
  giq::InputError e("scene.gltf", "meshes[2].primitives[0].indices", "index 7 out of range\n(3 vertices)");
  EXPECT_STREQ(e.what(), "scene.gltf: meshes[2].primitives[0].indices: index 7 out of range (3 vertices)");
  EXPECT_EQ(e.file(), "scene.gltf");
  EXPECT_EQ(e.field(), "meshes[2].primitives[0].indices");
}

TEST(InputError, OmitsEmptyParts) {
  EXPECT_STREQ(giq::InputError("", "--spp", "expected a positive integer").what(),
               "--spp: expected a positive integer");
}
