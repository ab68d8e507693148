#pragma once
// Helpers shared by the test executables (header-only).
#include <unistd.h>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "common/json_text.h"

namespace rpvio::test {

/// A fresh directory under the system temp folder, removed when the object goes out of scope.
class TempDir {
 public:
  explicit TempDir(const std::string& tag = "rpvio") {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            (tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

/// Runs a shell command; returns its exit code and stores stdout+stderr in `output`.
inline int runCommand(const std::string& command, std::string& output) {
  output.clear();
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof(buffer), pipe)) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The number after the first `"key":` in a JSON text (NaN when absent): enough to check the
/// apps' flat JSON outputs without a JSON library.
using ::rpvio::jsonNumber;

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline std::string dataDir() { return RPVIO_DATA_DIR; }
inline std::string binDir() { return RPVIO_BIN_DIR; }

}  // namespace rpvio::test
