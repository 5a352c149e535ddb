#pragma once
// A per-process scratch folder for a test binary, removed when the binary ends (a gtest global
// environment, registered at static initialisation, before RUN_ALL_TESTS).

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

namespace rocking_monitor::core::testing {

class TempRoot : public ::testing::Environment {
 public:
  /// Folder <tmp>/<prefix><pid>; not created until a test creates something below it.
  explicit TempRoot(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()))) {}
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

  /// Registers a TempRoot with gtest (which owns it) and returns it.
  static const TempRoot& registered(const std::string& prefix) {
    return *static_cast<TempRoot*>(::testing::AddGlobalTestEnvironment(new TempRoot(prefix)));
  }

 private:
  std::filesystem::path path_;
};

}  // namespace rocking_monitor::core::testing
