// Fuzzing the spec door every client goes through (io::parseJsonText, then validateSpec and
// estimateRun): random mutations of the example specs, as bytes and as JSON values, with a fixed
// seed. Whatever the input, the answer is a value, a SpecError naming a field, or a JSON parse
// error: never another exception (a type_error from reading a field as the wrong type would be a
// crash at the CLI and a 500 at the server), never a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "io/json_text.hpp"
#include "rupture/run.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> seedSpecs() {
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(fs::path(RUPTURE_SOURCE_DIR) / "examples")) {
    const std::string text = readText(entry.path());
    const Json j = Json::parse(text, nullptr, false);
    if (j.is_object() && j.contains("scenario")) out.push_back(text);
  }
  return out;
}

const std::vector<std::string> kTokens = {"1e400", "-1e400", "NaN", "-0", "0", "1e-320", "9007199254740993",
                                          "-9223372036854775809", "18446744073709551616", "null", "true", "\"\"",
                                          "\"\xff\xfe\"", "\"\\ud800\"", "[", "]", "{", "}", ",", ":", "\"x\":",
                                          std::string("\0", 1), "[[[[[[[[", "\"scenario\"", "1.7976931348623157e308"};

std::string mutateBytes(std::string text, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 4);
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    const std::size_t at = rng() % text.size();
    switch (kind(rng)) {
      case 0: text[at] = static_cast<char>(rng() & 0xff); break;                         // flip a byte
      case 1: text.erase(at, 1 + rng() % 16); break;                                    // delete a run
      case 2: text.insert(at, kTokens[rng() % kTokens.size()]); break;                   // insert a token
      case 3: text.insert(at, text.substr(rng() % text.size(), 1 + rng() % 32)); break;  // duplicate a run
      default: text.resize(at); break;                                                  // truncate
    }
  }
  return text;
}

Json randomValue(std::mt19937_64& rng) {
  switch (rng() % 9) {
    case 0: return nullptr;
    case 1: return (rng() & 1) != 0;
    case 2: return -static_cast<double>(rng() % 1000) * 1e-3;
    case 3: return 1e308;
    case 4: return static_cast<std::int64_t>(rng());
    case 5: return std::string("\xef\xbf\xbe") + "x";
    case 6: return Json::array({1, "a", nullptr});
    case 7: return Json::object({{"", 1}});
    default: return 0;
  }
}

/// Replaces, removes or retypes one value somewhere in the spec.
void mutateValue(Json& node, std::mt19937_64& rng) {
  if ((node.is_object() || node.is_array()) && !node.empty() && rng() % 4 != 0) {
    auto it = node.begin();
    std::advance(it, static_cast<long>(rng() % node.size()));
    if (rng() % 8 == 0) {
      if (node.is_object()) node.erase(it.key());
      else node.erase(it);
      return;
    }
    mutateValue(*it, rng);
    return;
  }
  node = randomValue(rng);
}

enum class Answer { Valid, SpecErrorAnswer, NotJson };

Answer answer(const std::string& text) {
  Json spec;
  try {
    spec = rupture::io::parseJsonText(text);
  } catch (const rupture::SpecError& e) {
    EXPECT_FALSE(e.field().empty());
    return Answer::SpecErrorAnswer;
  } catch (const nlohmann::json::parse_error&) {
    return Answer::NotJson;
  }
  try {
    const rupture::RunEstimate estimate = rupture::estimateRun(spec);
    EXPECT_GE(estimate.particles, 0.0);
    return Answer::Valid;
  } catch (const rupture::SpecError& e) {
    EXPECT_FALSE(e.field().empty()) << e.what();
    return Answer::SpecErrorAnswer;
  }
}

TEST(SpecFuzz, EveryMutationGetsAValueOrANamedError) {
  const std::vector<std::string> seeds = seedSpecs();
  ASSERT_FALSE(seeds.empty());
  std::mt19937_64 rng(20261123);
  int counts[3] = {0, 0, 0};
  constexpr int kCases = 4000;
  for (int n = 0; n < kCases; ++n) {
    const std::string& seed = seeds[static_cast<std::size_t>(n) % seeds.size()];
    std::string text;
    if (n % 2 == 0) {
      text = mutateBytes(seed, rng);
    } else {
      Json spec = Json::parse(seed);
      const int edits = 1 + static_cast<int>(rng() % 3);
      for (int e = 0; e < edits; ++e) mutateValue(spec, rng);
      text = spec.dump(-1, ' ', false, Json::error_handler_t::replace);
    }
    try {
      ++counts[static_cast<int>(answer(text))];
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << n << " threw " << typeid(e).name() << ": " << e.what() << "\ninput: " << text.substr(0, 400);
    }
  }
  // Both kinds of answer must be exercised, or the mutations are not reaching the validator.
  EXPECT_GT(counts[static_cast<int>(Answer::SpecErrorAnswer)], kCases / 10);
  EXPECT_GT(counts[static_cast<int>(Answer::NotJson)], kCases / 10);
  EXPECT_GT(counts[static_cast<int>(Answer::Valid)], 0);
  std::cout << "[ fuzz ] " << kCases << " cases: " << counts[0] << " valid, " << counts[1] << " spec errors, "
            << counts[2] << " not JSON\n";
}

}  // namespace
