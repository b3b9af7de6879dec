// io::readNamedText: a file's whole text under its path, and the path in every error; a text
// parsed from memory reports errors under the name it was given, as the same text read from disk.
#include "pkm/io/named_text.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using namespace std::string_literals;
using ::testing::HasSubstr;

fs::path tempFile(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

TEST(NamedTextTest, ReadsTheWholeFileUnderItsPath) {
  const std::string text = "a,b\r\n1,2\n\0x"s;
  const fs::path p = tempFile("pkm_named_text", text);
  const NamedText in = readNamedText(p.string());
  EXPECT_EQ(in.name, p.string());
  EXPECT_EQ(in.text, text);
  fs::remove(p);
}

TEST(NamedTextTest, AMissingFileIsNamed) {
  try {
    (void)readNamedText("/nonexistent/dir/x.csv");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/dir/x.csv"));
    EXPECT_THAT(e.what(), HasSubstr("cannot open the file"));
  }
}

TEST(NamedTextTest, ReadsSeveralInOrder) {
  const fs::path a = tempFile("pkm_named_a", "1");
  const fs::path b = tempFile("pkm_named_b", "2");
  const auto all = readNamedTexts({b.string(), a.string()});
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].text, "2");
  EXPECT_EQ(all[1].text, "1");
  fs::remove(a);
  fs::remove(b);
}

TEST(NamedTextTest, AnUploadGetsTheSameMessageAsTheFile) {
  const std::string text = "x,y\n1,2\n3\n";
  const fs::path p = tempFile("pkm_named_bad", text);
  std::string from_disk, from_memory;
  try {
    (void)TextTable::read(p.string());
  } catch (const IoError& e) {
    from_disk = e.what();
  }
  try {
    (void)TextTable::parse(text, p.string());
  } catch (const IoError& e) {
    from_memory = e.what();
  }
  EXPECT_THAT(from_disk, HasSubstr(p.string() + ":3:"));
  EXPECT_EQ(from_disk, from_memory);
  fs::remove(p);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
