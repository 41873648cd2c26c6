// Provenance (io/provenance.hpp, docs/provenance.md): SHA-256 against FIPS 180-4's examples and
// block-boundary lengths; every result file's /provenance group holds the build, host, threads,
// times, the digest of the very spec text stored in /spec, and the spec's seeds; a run through
// runSpec records them for its scenario.
#include "io/provenance.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <regex>
#include <string>

#include "io/sha256.hpp"
#include "engine/test_elastic_properties_support.hpp"
#include "io/result_file.hpp"
#include "rupture/run.hpp"
#include "support/test_support.hpp"

namespace rupture {
namespace {

using io::Hdf5File;
using rupture::testing::ScratchDir;

TEST(Sha256, MatchesTheStandardsExamples) {
  // FIPS 180-4 / NIST CSRC examples.
  EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256Hex(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, PadsAtEveryBlockBoundary) {
  // Lengths on both sides of the 55/56-byte padding split and the 64-byte block (Python's hashlib).
  EXPECT_EQ(sha256Hex(std::string(55, 'x')), "d5e285683cd4efc02d021a5c62014694958901005d6f71e89e0989fac77e4072");
  EXPECT_EQ(sha256Hex(std::string(56, 'x')), "04c26261370ee7541549d16dee320c723e3fd14671e66a099afe0a377c16888e");
  EXPECT_EQ(sha256Hex(std::string(63, 'x')), "75220b47218278e656f2013bb8f0c455a25eaf01e86c64924e9d48d89776d6f2");
  EXPECT_EQ(sha256Hex(std::string(64, 'x')), "7ce100971f64e7001e8fe5a51973ecdfe1ced42befe7ee8d5fd6219506b5393c");
  EXPECT_EQ(sha256Hex(std::string(119, 'x')), "000b48d4edf0fa7bee3c6236ecd2785baa5db4eeb8bb54341b029e0d9fa5fb0c");
}

TEST(Provenance, SeedsAreFoundWhereverTheSpecHasThem) {
  const nlohmann::json spec = {{"sample", {{"seed", 7}, {"size", {1, 2}}}},
                               {"loading", {{"noise_seed", 11}, {"seedling", 3}}},
                               {"material", {{"seed", "not a number"}}}};
  EXPECT_EQ(io::specSeeds(spec), (nlohmann::json{{"sample.seed", 7}, {"loading.noise_seed", 11}}));
  EXPECT_EQ(io::specSeeds(nlohmann::json{{"scenario", "dam-break"}}), nlohmann::json::object());
}

/// The attributes every result's /provenance holds, checked for their form.
void expectProvenance(const Hdf5File& f, int threads) {
  const std::string g = "/provenance";
  EXPECT_EQ(f.readAttributeString(g, "rupture_version"), RUPTURE_VERSION);
  const std::string commit = f.readAttributeString(g, "git_commit");
  EXPECT_TRUE(std::regex_match(commit, std::regex("[0-9a-f]{40}(-dirty)?|unknown"))) << commit;
  EXPECT_FALSE(f.readAttributeString(g, "compiler").empty());
  EXPECT_NE(f.readAttributeString(g, "compile_flags").find("-Wall"), std::string::npos);
  EXPECT_EQ(f.readAttributeString(g, "host_processor"), io::hostProcessor());
  EXPECT_EQ(f.readAttributeInt(g, "threads"), threads);
  const std::regex utc("\\d{4}-\\d\\d-\\d\\dT\\d\\d:\\d\\d:\\d\\dZ");
  EXPECT_TRUE(std::regex_match(f.readAttributeString(g, "started_utc"), utc));
  EXPECT_TRUE(std::regex_match(f.readAttributeString(g, "finished_utc"), utc));
  EXPECT_LE(f.readAttributeString(g, "started_utc"), f.readAttributeString(g, "finished_utc"));
  // The digest is of the spec text as stored, so anyone can check it.
  EXPECT_EQ(f.readAttributeString(g, "spec_sha256"), sha256Hex(f.readAttributeString("/spec", "json")));
}

TEST(Provenance, EveryResultFileRecordsIt) {
  ScratchDir dir;
  const std::string path = (dir.path() / "r.h5").string();
  const nlohmann::json resolved = {{"scenario", "x"}, {"sample", {{"seed", 42}}}};
  {
    io::ResultFile file(path, "x");
    file.writeSpec(resolved, resolved);
    file.finish(true);
  }
  const Hdf5File f = Hdf5File::openReadOnly(path);
  expectProvenance(f, omp_get_max_threads());
  EXPECT_EQ(f.readAttributeString("/provenance", "spec_sha256"), sha256Hex(resolved.dump()));
  EXPECT_EQ(nlohmann::json::parse(f.readAttributeString("/provenance", "seeds")), (nlohmann::json{{"sample.seed", 42}}));
}

TEST(Provenance, ARunRecordsItsThreadsAndSeeds) {
  ScratchDir dir;
  const std::string path = (dir.path() / "run.h5").string();
  nlohmann::json spec = test::smallBeamElasticPropertiesSpec();
  spec["sample"]["seed"] = 5;
  RunControl control;
  ASSERT_TRUE(runSpec(spec, path, control, 2).completed);
  const Hdf5File f = Hdf5File::openReadOnly(path);
  expectProvenance(f, 2);
  EXPECT_EQ(nlohmann::json::parse(f.readAttributeString("/provenance", "seeds")), (nlohmann::json{{"sample.seed", 5}}));
}

}  // namespace
}  // namespace rupture
