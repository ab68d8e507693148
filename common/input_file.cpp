#include "common/input_file.h"

#include <filesystem>

#include "common/input_error.h"

namespace rpvio {

void requireRegularFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_regular_file(status)) return;
  if (std::filesystem::is_directory(status))
    throw InputError(path, "", what + " expected, found a directory");
  if (std::filesystem::exists(status))
    throw InputError(path, "", what + " expected, found a special file");
  throw InputError(path, "", what + " not found");
}

std::ifstream openInputFile(const std::string& path, const std::string& what) {
  requireRegularFile(path, what);
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open " + what);
  return in;
}

}  // namespace rpvio
