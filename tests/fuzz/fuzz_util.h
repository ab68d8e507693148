#pragma once
// Helpers shared by the fuzz targets (header-only): the input bytes as a file, since the readers
// take paths, and the checks that turn a wrong result into a crash libFuzzer records.
#include <unistd.h>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.h"

namespace rpvio::fuzz {

/// The fuzzer's bytes in `<tmp>/rpvio_fuzz_<pid>/<name>` (one folder per process), removed with
/// the folder on destruction.
class InputFile {
 public:
  InputFile(const uint8_t* data, size_t size, const std::string& name)
      : dir_(std::filesystem::temp_directory_path() /
             ("rpvio_fuzz_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / name).string();
    std::ofstream(path_, std::ios::binary).write(reinterpret_cast<const char*>(data), size);
  }
  ~InputFile() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::filesystem::path dir_;
  std::string path_;
};

/// Runs a reader: InputError is the expected outcome of bad input; any other exception escapes
/// and libFuzzer reports it (uncaught exception, abort).
template <typename Fn>
void readExpectingOnlyInputError(Fn read) {
  try {
    read();
  } catch (const InputError&) {
  }
}

/// Aborts (a libFuzzer crash) with a message when a reader returned something it must not.
inline void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "rpvio fuzz check failed: %s\n", what);
  std::abort();
}

inline bool isUnit(const Eigen::Quaterniond& q) { return std::abs(q.norm() - 1.0) < 1e-9; }

inline bool isRotation(const Eigen::Matrix3d& r) {
  return (r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-9 &&
         std::abs(r.determinant() - 1.0) < 1e-9;
}

}  // namespace rpvio::fuzz
