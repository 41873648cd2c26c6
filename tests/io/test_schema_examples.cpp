// Every scenario's JSON Schema carries a complete example spec ("examples"): the browser's
// submission form starts from it, so it must be a valid spec of its scenario.
#include <gtest/gtest.h>

#include "rupture/run.hpp"

namespace rupture {
namespace {

TEST(SchemaExamples, EveryScenarioHasAValidExample) {
  for (const ScenarioInfo& s : listScenarios()) {
    SCOPED_TRACE(s.name);
    const nlohmann::json schema = scenarioSchema(s.name);
    ASSERT_TRUE(schema.contains("examples") && schema["examples"].is_array() && !schema["examples"].empty());
    for (nlohmann::json example : schema["examples"]) {
      EXPECT_FALSE(example.contains("scenario")) << "an example is the inputs of a request: the URL names the scenario";
      example["scenario"] = s.name;
      EXPECT_NO_THROW(validateSpec(example)) << example.dump();
    }
  }
}

}  // namespace
}  // namespace rupture
