// Resumes on two OpenMP threads, with systems large enough for the loops to fork (8192 bonds or
// particles, core/parallel.hpp): the parallel paths of the bonded loops and of SPH, their
// per-thread lists and reductions, resume bit for bit on the same thread count.
#include <filesystem>

#include <gtest/gtest.h>

#include "checkpoint/checkpoint_support.hpp"

namespace rupture::test {
namespace {

TEST(ResumeOnTwoThreads, PeridynamicPlate) {
  const nlohmann::json spec = {
      {"scenario", "impact"},
      {"dimension", 2},
      {"sample", {{"lattice", "square"}, {"size", {0.01, 0.005}}, {"spacing", 1.25e-4},
                  {"notches", {{{"start", {0.0, 0.0025}}, {"end", {0.004, 0.0025}}}}}}},
      {"material", {{"model", "pmb"}, {"density", 2440}, {"pmb", {{"young_modulus", 72e9}, {"fracture_energy", 3.8}}}}},
      {"loading", {{"velocity_regions", {{{"min", {0.0, 0.0048}}, {"max", {0.01, 0.005}}, {"velocity", {0.0, 8.0}}, {"ramp_time", 5e-7}},
                                         {{"min", {0.0, 0.0}}, {"max", {0.01, 0.0002}}, {"velocity", {0.0, -8.0}}, {"ramp_time", 5e-7}}}}}},
      {"run", {{"end_time", 3e-6}}}};
  rupture::testing::ScratchDir dir;
  const nlohmann::json summary = expectResumedRunMatches(spec, dir.path(), 2, 2);
  EXPECT_GT(summary.value("broken_bonds", std::int64_t{0}), 0);
}

TEST(ResumeOnTwoThreads, DamBreak) {
  const nlohmann::json spec = {
      {"scenario", "dam-break"},
      {"dimension", 2},
      {"geometry", {{"column_width", 0.057}, {"column_height", 0.114}, {"tank_length", 0.2}, {"tank_height", 0.15}}},
      {"resolution", {{"spacing", 0.001}}},
      {"run", {{"end_time", 0.01}}}};
  rupture::testing::ScratchDir dir;
  expectResumedRunMatches(spec, dir.path(), 2, 2);
}

}  // namespace
}  // namespace rupture::test
