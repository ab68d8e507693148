#pragma once
// Bad input (missing file, malformed line, truncated rawlog, ...): one line naming the file and the
// position. Apps catch it, print what() on one line and exit with kExitBadInput.
#include <stdexcept>
#include <string>

namespace rpvio {

constexpr int kExitBadInput = 2;

class InputError : public std::runtime_error {
 public:
  /// position: "line 12", "entry 345", "" when the whole file is at fault.
  InputError(const std::string& file, const std::string& position, const std::string& reason)
      : std::runtime_error(file + (position.empty() ? "" : ":" + position) + ": " + reason),
        file_(file),
        position_(position) {}
  const std::string& file() const { return file_; }
  const std::string& position() const { return position_; }

 private:
  std::string file_;
  std::string position_;
};

}  // namespace rpvio
