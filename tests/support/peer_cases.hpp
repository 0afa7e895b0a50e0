#pragma once
// Locates the shared reference data beside the repository: CONTACT's cases
// (../shared/peer-cases, or FASTNORM_PEER_CASES) and the MBench profiles (../shared/profiles).

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace fastnorm::test {

inline std::string peer_cases_dir() {
  const char* from_environment = std::getenv("FASTNORM_PEER_CASES");
  return from_environment ? from_environment : FASTNORM_PEER_CASES_DIR;
}

/// The sampled Manchester-benchmark profile `name` (../shared/profiles, or the folder
/// named by FASTNORM_PROFILES), or "" when it is absent (the caller then WARNs and skips).
inline std::string shared_profile(const std::string& name) {
  const char* from_environment = std::getenv("FASTNORM_PROFILES");
  const std::filesystem::path path = std::filesystem::path(from_environment ? from_environment : FASTNORM_PROFILES_DIR) / name;
  return std::filesystem::is_regular_file(path) ? path.string() : std::string();
}

/// CONTACT's tangential results on Hertzian cases (../shared/peer-tangential/hertz.tsv, or
/// the folder named by FASTNORM_PEER_TANGENTIAL), or "" when absent.
inline std::string peer_tangential_file() {
  const char* from_environment = std::getenv("FASTNORM_PEER_TANGENTIAL");
  const std::filesystem::path path =
      std::filesystem::path(from_environment ? from_environment : FASTNORM_PEER_TANGENTIAL_DIR) / "hertz.tsv";
  return std::filesystem::is_regular_file(path) ? path.string() : std::string();
}

/// Sorted paths of the peer cases whose file name starts with `prefix`; empty when the
/// folder is absent (the caller then WARNs and skips).
inline std::vector<std::string> peer_case_files(const std::string& prefix = "") {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  const fs::path dir = peer_cases_dir();
  if (!fs::is_directory(dir)) return files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".case" && name.rfind(prefix, 0) == 0) {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// The reference data a test needs is absent: a warning and a skip, or a failure when
/// FASTNORM_REQUIRE_SHARED is set (as .ci/run sets it: a CI without the data must not pass
/// these tests vacuously).
inline void reference_data_missing(const std::string& what) {
  if (std::getenv("FASTNORM_REQUIRE_SHARED")) FAIL(what << " (FASTNORM_REQUIRE_SHARED is set)");
  WARN(what << ": skipped");
}

}  // namespace fastnorm::test
