/// @file
/// @brief Shared fixture of the CLI tests: runs the built `pkm` binary (PKM_BINARY) as a subprocess
/// in a fresh temporary folder and captures its exit code, standard output and standard error.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pkm::test {

/// Exit code of pkm for usage and input errors.
inline constexpr int kExitUsage = 2;

/// What one run of the CLI did.
struct CliRun {
  int code = -1;
  std::string out, err;
};

/// The lines of `text`.
inline std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

/// The comma-separated fields of `line`.
inline std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = line.find(',', pos);
    fields.push_back(
        line.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return fields;
}

/// A whole field as a number (the test fails if characters are left over).
inline double num(const std::string& s) {
  std::size_t used = 0;
  const double v = std::stod(s, &used);
  EXPECT_EQ(used, s.size()) << s;
  return v;
}

/// Base fixture: a temporary folder per test and helpers to write inputs and run `pkm`.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("pkm_cli_test_") + std::to_string(::getpid()) + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  /// `s` in single quotes for /bin/sh.
  static std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) {
      if (c == '\'')
        q.append("'\\''");
      else
        q.push_back(c);
    }
    q.push_back('\'');
    return q;
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream out(dir_ / name, std::ios::binary);
    out << content;
    return path(name);
  }

  static std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  /// Runs `pkm ARGS` (each quoted) with stdin from `stdin_file` (or /dev/null); captures
  /// everything.
  CliRun pkm(const std::vector<std::string>& args,
             const std::string& stdin_file = "/dev/null") const {
    std::string cmd = quote(PKM_BINARY);
    for (const auto& a : args) cmd.append(" ").append(quote(a));
    cmd.append(" < ").append(quote(stdin_file));
    cmd.append(" > ").append(quote(path("stdout.txt")));
    cmd.append(" 2> ").append(quote(path("stderr.txt")));
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "stdout.txt");
    r.err = slurp(dir_ / "stderr.txt");
    return r;
  }

  /// Expects exit code 2 and "pkm: error: " on stderr containing `where`; returns stderr.
  static std::string expectUsageError(const CliRun& r, const std::string& where) {
    EXPECT_EQ(r.code, kExitUsage) << r.err;
    EXPECT_THAT(r.err, ::testing::HasSubstr(where));
    return r.err;
  }

  std::filesystem::path dir_;
};

}  // namespace pkm::test
