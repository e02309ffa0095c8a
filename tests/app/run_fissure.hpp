#pragma once
// Runs the fissure executable and captures its exit code and output.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

namespace fissure::test {

struct Outcome {
  int exit_code;
  std::string output;  // stdout and stderr together
};

// Runs a shell command line (/bin/sh), e.g. the binary under `ulimit`.
inline Outcome run_shell(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  Outcome outcome{-1, ""};
  if (!pipe) return outcome;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) outcome.output += buffer.data();
  const int status = pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return outcome;
}

inline Outcome run_fissure(const std::string& args) {
  return run_shell(std::string(FISSURE_BINARY) + " " + args);
}

// A fresh, empty folder named after the running test and `name`: ctest -j runs each test in a
// process of its own, side by side, so two tests never share (and delete) one folder.
inline std::filesystem::path scratch_dir(const std::string& name) {
  std::string test = "outside_a_test";
  if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
    test = std::string(info->test_suite_name()) + "." + info->name();
  for (char& c : test)
    if (c == '/') c = '_';  // parameterised tests: Prefix/Suite.Name/0
  const auto dir = std::filesystem::temp_directory_path() / ("fissure_test_" + test + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The top-level keys of a run's summary.json with their values as written (strings quoted);
// nested maps such as integrator_statistics are skipped.
inline std::map<std::string, std::string> read_summary(const std::filesystem::path& path) {
  const std::string text = slurp(path);
  std::map<std::string, std::string> values;
  static const std::regex pair(R"re("([A-Za-z_]+)"\s*:\s*("[^"]*"|[^,\s}]+))re");
  int depth = 0;
  std::size_t scanned = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), pair); it != std::sregex_iterator();
       ++it) {
    const auto at = static_cast<std::size_t>(it->position());
    for (; scanned < at; ++scanned)
      depth += text[scanned] == '{' ? 1 : text[scanned] == '}' ? -1 : 0;
    if (depth == 1) values[(*it)[1]] = (*it)[2];
  }
  return values;
}

}  // namespace fissure::test
