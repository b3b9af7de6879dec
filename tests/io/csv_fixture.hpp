/// @file
/// @brief Shared by the csv tests: a fixture that writes CSV files byte for byte to a fresh folder
/// per test and gives the error of reading one.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "support/scratch_files.hpp"

namespace pkm::test {

/// A fresh temporary directory per test, removed afterwards (suite name CsvTest).
class CsvTest : public ScratchDirTest {
 protected:
  CsvTest() : ScratchDirTest("csv_test") {}

  /// The message of the pkm::IoError thrown by reading all of `content` with columns `cols`
  /// (empty if none is thrown).
  std::string errorOf(const std::string& content,
                      const std::vector<std::string>& cols,
                      const std::string& name = "data.csv") const {
    const std::string path = write(name, content);
    try {
      io::CsvReader r(path, cols);
      std::vector<double> v(cols.size());
      while (r.next(v)) {
      }
    } catch (const pkm::IoError& e) {
      return e.what();
    }
    return {};
  }
};

}  // namespace pkm::test
