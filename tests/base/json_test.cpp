// The JSON reader every giq reader uses: nesting depth bounded, duplicate keys refused, both
// and bad text as InputError naming the file and where; valid documents as nlohmann reads them.

#include "giq/base/json.h"

#include <gtest/gtest.h>

#include <string>

#include "giq/base/error.h"

namespace {

std::string nested(int depth) { return std::string(size_t(depth), '[') + std::string(size_t(depth), ']'); }

TEST(Json, ParsesValidDocumentsAsNlohmannDoes) {
  const std::string text = R"({"b": [1, 2.5, {"c": null}], "a": "x", "d": {"a": true}})";
  EXPECT_EQ(giq::parse_json(text, "f.json"), nlohmann::json::parse(text));
  // The ordered variant keeps the keys' order.
  EXPECT_EQ(giq::parse_ordered_json(text, "f.json").begin().key(), "b");
  // The same key in different objects is not a duplicate.
  EXPECT_NO_THROW(giq::parse_json(R"({"a": {"a": 1}, "b": [{"a": 1}, {"a": 2}]})", "f.json"));
}

TEST(Json, NestingUpToTheLimitIsAcceptedBeyondItRefused) {
  EXPECT_NO_THROW(giq::parse_json(nested(giq::kMaxJsonDepth), "f.json"));
  for (int depth : {giq::kMaxJsonDepth + 1, 30000, 1000000}) {
    SCOPED_TRACE(depth);
    try {
      giq::parse_json(R"({"extras": )" + nested(depth) + "}", "f.json");
      FAIL() << "accepted";
    } catch (const giq::InputError& e) {
      EXPECT_EQ(e.file(), "f.json");
      EXPECT_EQ(e.field(), "JSON");
      EXPECT_NE(std::string(e.what()).find("nest deeper than 256 levels at extras[]"), std::string::npos) << e.what();
    }
  }
}

TEST(Json, ARepeatedKeyIsRefusedWithItsPlace) {
  try {
    giq::parse_json(R"({"cases": [{"bounds": {"relmse": 0.01, "relmse": 10}}]})", "gate.json");
    FAIL() << "accepted";
  } catch (const giq::InputError& e) {
    EXPECT_EQ(e.file(), "gate.json");
    EXPECT_EQ(e.field(), "cases[].bounds.relmse");
    EXPECT_NE(std::string(e.what()).find("\"relmse\" appears twice"), std::string::npos) << e.what();
  }
  EXPECT_THROW(giq::parse_ordered_json(R"({"a": 1, "a": 1})", "f.json"), giq::InputError);
}

TEST(Json, TextThatIsNotJsonNamesTheLineAndColumn) {
  try {
    giq::parse_json("{\"a\": 1,\n ]", "f.json");
    FAIL() << "accepted";
  } catch (const giq::InputError& e) {
    EXPECT_EQ(e.field(), "JSON");
    EXPECT_NE(std::string(e.what()).find("not valid JSON: parse error at line 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(giq::read_json("/nonexistent/f.json"), giq::InputError);
}

}  // namespace
