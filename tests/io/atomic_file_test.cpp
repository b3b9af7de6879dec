// io::AtomicFile / writeFileAtomic: the destination appears whole or not at all, an existing file
// is refused or replaced as asked, and no temporary file is left behind.
#include "pkm/io/atomic_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pkm_atomic_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  [[nodiscard]] std::size_t entries() const {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  fs::path dir_;
};

TEST_F(AtomicFileTest, WritesInPiecesAndPublishesOnCommit) {
  const fs::path p = dir_ / "out.txt";
  AtomicFile f(p, Overwrite::kRefuse);
  f.write("first ");
  f.write("second");
  EXPECT_FALSE(fs::exists(p));  // nothing visible before commit
  f.commit();
  EXPECT_EQ(readFileText(p), "first second");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, AnAbandonedWriteLeavesTheOldFileAndNoTemporary) {
  const fs::path p = dir_ / "out.txt";
  writeFileAtomic(p, "the user's file", Overwrite::kRefuse);
  try {
    AtomicFile f(p, Overwrite::kAllow);
    f.write("half");
    throw std::runtime_error("interrupted");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(readFileText(p), "the user's file");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, RefusesOrReplacesAnExistingFile) {
  const fs::path p = dir_ / "out.txt";
  writeFileAtomic(p, "one", Overwrite::kRefuse);
  try {
    writeFileAtomic(p, "two", Overwrite::kRefuse);
    FAIL() << "overwrote";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("out.txt exists; pass --force to overwrite it"));
  }
  EXPECT_EQ(readFileText(p), "one");
  writeFileAtomic(p, "two", Overwrite::kAllow);
  EXPECT_EQ(readFileText(p), "two");
}

TEST_F(AtomicFileTest, UnwritableDestinationsAndMissingFilesAreIoErrors) {
  EXPECT_THROW(writeFileAtomic(dir_ / "no" / "such" / "dir.txt", "x", Overwrite::kAllow), IoError);
  EXPECT_THROW((void)readFileText(dir_ / "missing.txt"), IoError);
  EXPECT_EQ(entries(), 0u);
}

TEST_F(AtomicFileTest, OutputDirectoriesAreCreatedAndNotOverwrittenWithoutForce) {
  const fs::path out = dir_ / "a" / "b";
  prepareOutputDirectory(out, false);
  EXPECT_TRUE(fs::is_directory(out));
  prepareOutputDirectory(out, false);  // empty: fine
  writeFileAtomic(out / "x.txt", "x", Overwrite::kRefuse);
  try {
    prepareOutputDirectory(out, false);
    ADD_FAILURE() << "a non-empty directory was accepted";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("exists and is not empty; refusing to overwrite (use --force)"));
  }
  prepareOutputDirectory(out, true);
  EXPECT_EQ(readFileText(out / "x.txt"), "x");  // force writes into it, deletes nothing
  EXPECT_THROW(prepareOutputDirectory(out / "x.txt", true), IoError);  // a file, not a folder
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
