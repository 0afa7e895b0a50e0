#pragma once
// Locates CONTACT's reference cases (../shared/peer-cases beside the repository, or the
// folder named by the environment variable FASTNORM_PEER_CASES).

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

}  // namespace fastnorm::test
