// ResultFile's life cycle: written as RESULT.part and renamed onto RESULT by finish(); deleted when
// abandoned; and a RESULT that already ends in ".part" (the job server's run-k.h5.part) written in
// place and left for the caller to rename, so a result goes through one rename, not two.
#include "io/result_file.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using rupture::io::Hdf5File;
using rupture::io::ResultFile;

namespace {

class ResultFileTest : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("rupture_result_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  fs::path m_dir;
};

std::int64_t completedFlag(const fs::path& path) {
  return Hdf5File::openReadOnly(path.string()).readAttributeInt("/", "completed");
}

TEST_F(ResultFileTest, IsWrittenAsPartAndRenamedOntoTheResultWhenFinished) {
  const fs::path result = m_dir / "run.h5";
  {
    ResultFile file(result.string(), "dam-break");
    EXPECT_TRUE(fs::exists(m_dir / "run.h5.part"));
    EXPECT_FALSE(fs::exists(result));
    file.finish(true);
  }
  EXPECT_TRUE(fs::exists(result));
  EXPECT_FALSE(fs::exists(m_dir / "run.h5.part"));
  EXPECT_EQ(completedFlag(result), 1);
}

TEST_F(ResultFileTest, AnUnfinishedFileIsDeleted) {
  { ResultFile file((m_dir / "run.h5").string(), "dam-break"); }
  EXPECT_FALSE(fs::exists(m_dir / "run.h5"));
  EXPECT_FALSE(fs::exists(m_dir / "run.h5.part"));
}

TEST_F(ResultFileTest, APartPathIsTheCallersToRename) {
  const fs::path part = m_dir / "run-0.h5.part";
  {
    ResultFile file(part.string(), "dam-break");
    file.finish(false);
  }
  EXPECT_TRUE(fs::exists(part)) << "written in place, complete or not";
  EXPECT_FALSE(fs::exists(m_dir / "run-0.h5.part.part"));
  EXPECT_FALSE(fs::exists(m_dir / "run-0.h5"));
  EXPECT_EQ(completedFlag(part), 0);

  { ResultFile file(part.string(), "dam-break"); }  // abandoned: the caller's temporary goes too
  EXPECT_FALSE(fs::exists(part));
}

}  // namespace
