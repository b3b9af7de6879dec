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

namespace pkm::test {

/// A fresh temporary directory per test, removed afterwards (suite name CsvTest).
class CsvTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("pkm_csv_test_") + std::to_string(::getpid()) + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  /// Writes `content` byte for byte to DIR/name and returns the path.
  std::string write(const std::string& name, const std::string& content) const {
    const std::filesystem::path p = dir_ / name;
    std::ofstream out(p, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    return p.string();
  }

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

  std::filesystem::path dir_;
};

}  // namespace pkm::test
