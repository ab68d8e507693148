#pragma once
// A small INI reader that keeps line numbers, so every error names the file and the line.
// `key = value` lines inside `[section]`s; `#` and `;` start comments.
#include <map>
#include <string>
#include <vector>

namespace rpvio {

class IniFile {
 public:
  /// Throws InputError when the file is missing or a line is not `key = value` / `[section]`.
  explicit IniFile(const std::string& path);

  const std::string& path() const { return path_; }
  bool has(const std::string& section, const std::string& key) const;
  /// Exactly `count` finite numbers separated by spaces; InputError otherwise (missing key too).
  std::vector<double> numbers(const std::string& section, const std::string& key,
                              size_t count) const;
  double number(const std::string& section, const std::string& key) const;
  double numberOr(const std::string& section, const std::string& key, double fallback) const;
  std::string text(const std::string& section, const std::string& key) const;
  std::string textOr(const std::string& section, const std::string& key,
                     const std::string& fallback) const;
  bool flagOr(const std::string& section, const std::string& key, bool fallback) const;
  int line(const std::string& section, const std::string& key) const;

 private:
  struct Value {
    std::string text;
    int line = 0;
  };
  std::string path_;
  std::map<std::string, std::map<std::string, Value>> sections_;
};

}  // namespace rpvio
