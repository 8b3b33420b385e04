// A fresh folder of one test's own under the system's temporary folder,
// removed with everything in it when the test ends (pass or fail), so runs
// of the suite leave nothing behind.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <system_error>

namespace relight::test {

class TempDir {
 public:
  // Named for the process, the test and `label` (to tell several apart).
  explicit TempDir(const std::string& label = "") {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string test = info ? std::string(info->test_suite_name()) + "_" + info->name() : "x";
    std::string name = "relight_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" + test;
    if (!label.empty()) name += "_" + label;
    for (char& c : name)
      if (c == '/') c = '_';  // a parameterised test's name
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  operator const std::filesystem::path&() const { return path_; }
  std::string string() const { return path_.string(); }
  std::filesystem::path operator/(const std::filesystem::path& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace relight::test
