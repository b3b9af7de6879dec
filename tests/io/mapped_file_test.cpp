#include "pkm/io/mapped_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

TEST(MappedFile, HoldsAFilesBytes) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "pkm_mapped_file_test.txt";
  const std::string text = "x,y\n1,2\n" + std::string(100000, 'a');
  std::ofstream(path, std::ios::binary) << text;
  MappedFile f = MappedFile::open(path.string());
  EXPECT_EQ(f.bytes(), text);
  EXPECT_EQ(f.name(), path.string());
  const MappedFile moved = std::move(f);
  EXPECT_EQ(moved.bytes(), text);
  EXPECT_TRUE(f.bytes().empty());  // NOLINT(bugprone-use-after-move): moved-from is empty
  std::ofstream(path, std::ios::binary | std::ios::trunc).flush();
  EXPECT_TRUE(MappedFile::open(path.string()).bytes().empty());
  std::filesystem::remove(path);
}

TEST(MappedFile, NamesTheFileItCannotOpen) {
  try {
    (void)MappedFile::open("/nonexistent/pkm.csv");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/nonexistent/pkm.csv: cannot open the file: No such file or directory");
  }
  EXPECT_THROW((void)MappedFile::open(std::filesystem::temp_directory_path().string()), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
