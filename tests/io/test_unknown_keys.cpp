// The did-you-mean distance and the schema walk that finds unknown keys.
#include <gtest/gtest.h>

#include "io/unknown_keys.hpp"
#include "rupture/spec_error.hpp"

namespace rupture::io {
namespace {

TEST(UnknownKeys, EditDistance) {
  EXPECT_EQ(editDistance("strain_rte", "strain_rate"), 1u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("same", "same"), 0u);
}

TEST(UnknownKeys, NearestKeyOnlyForLikelyTypos) {
  const std::vector<std::string> keys = {"strain_rate", "initial_velocity", "seed"};
  EXPECT_EQ(nearestKey("strain_rte", keys), "strain_rate");
  EXPECT_EQ(nearestKey("Strain_Rate", keys), "strain_rate");
  EXPECT_EQ(nearestKey("sed", keys), "seed");
  EXPECT_EQ(nearestKey("colour", keys), "");
  EXPECT_EQ(nearestKey("x", keys), "");
}

TEST(UnknownKeys, SchemaWalkNamesThePathAndTheGuess) {
  const nlohmann::json schema = nlohmann::json::parse(R"({
    "type": "object", "additionalProperties": false,
    "properties": {
      "loading": {"type": "object", "additionalProperties": false,
                  "properties": {"strain_rate": {}, "initial_velocity": {}}},
      "notches": {"type": "array", "items": {"type": "object", "additionalProperties": false,
                  "properties": {"start": {}, "end": {}}}},
      "interblock": {"type": "object", "additionalProperties": false, "properties": {"default": {}},
                     "patternProperties": {"^[0-9]+_[0-9]+$": {}}}
    }})");
  EXPECT_NO_THROW(rejectUnknownKeys(nlohmann::json::parse(R"({"loading": {"strain_rate": 1}, "interblock": {"0_1": 2}})"), schema));
  try {
    rejectUnknownKeys(nlohmann::json::parse(R"({"loading": {"strain_rte": 1}})"), schema);
    FAIL() << "no error";
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "loading.strain_rte");
    EXPECT_NE(e.allowed().find("did you mean 'strain_rate'?"), std::string::npos) << e.what();
  }
  try {
    rejectUnknownKeys(nlohmann::json::parse(R"({"notches": [{"start": 0}, {"ends": 1}]})"), schema);
    FAIL() << "no error";
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "notches[1].ends");
    EXPECT_NE(e.allowed().find("did you mean 'end'?"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rupture::io
