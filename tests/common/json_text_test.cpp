// The JSON writer of the apps' files: layout, escaping, numbers, and the reader of one number.
#include <gtest/gtest.h>

#include <cmath>

#include "common/json_text.h"

namespace rpvio {
namespace {

TEST(JsonObject, TopLevelMembersOnePerLineObjectArraysOneElementPerLine) {
  const std::string json =
      JsonObject()
          .text("name", "a \"b\"\n")
          .integer("count", 12345678901LL)
          .flag("ok", true)
          .numbers("xyz", {1, 0.5, -2})
          .object("inner", JsonObject().number("t", 1.5).null("none"))
          .objects("runs", {JsonObject().integer("k", 0), JsonObject().integer("k", 1)})
          .objects("empty", {})
          .str();
  EXPECT_EQ(json,
            "{\n"
            "  \"name\": \"a \\\"b\\\"\\n\",\n"
            "  \"count\": 12345678901,\n"
            "  \"ok\": true,\n"
            "  \"xyz\": [1, 0.5, -2],\n"
            "  \"inner\": {\"t\": 1.5, \"none\": null},\n"
            "  \"runs\": [\n"
            "    {\"k\": 0},\n"
            "    {\"k\": 1}\n"
            "  ],\n"
            "  \"empty\": []\n"
            "}\n");
  EXPECT_EQ(JsonObject().str(), "{}\n");
}

TEST(JsonObject, NumbersKeepTheirDigitsAndNonFiniteOnesAreNull) {
  const double third = 1.0 / 3;
  EXPECT_EQ(JsonObject().number("x", third).oneLine(), "{\"x\": 0.333333}");
  const std::string exact = JsonObject(17).number("x", third).oneLine();
  EXPECT_EQ(jsonNumber(exact, "x"), third) << exact;
  EXPECT_EQ(JsonObject().number("x", NAN).number("y", INFINITY).oneLine(),
            "{\"x\": null, \"y\": null}");
}

TEST(JsonNumber, ReadsTheFirstKeyAndGivesNanWhenAbsentOrNull) {
  const std::string json = JsonObject().number("a", 2.5).null("b").integer("c", 7).str();
  EXPECT_EQ(jsonNumber(json, "a"), 2.5);
  EXPECT_TRUE(std::isnan(jsonNumber(json, "b")));
  EXPECT_EQ(jsonNumber(json, "c"), 7);
  EXPECT_TRUE(std::isnan(jsonNumber(json, "d")));
}

}  // namespace
}  // namespace rpvio
