#pragma once
// A small INI reader that keeps line numbers, so every error names the file and the line.
// `key = value` lines inside `[section]`s; `#` and `;` start comments. A key given twice in a
// section is an error (the second would silently win).
#include <map>
#include <set>
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

  struct KeyRef {
    std::string section, key;
    int line = 0;
  };
  /// The keys nobody asked for (has(), or any getter) so far, in file order: unknown keys once
  /// every reader of the file has read its options.
  std::vector<KeyRef> unreadKeys() const;
  /// Whether any key of `section` was asked for (present or not).
  bool sectionAskedFor(const std::string& section) const;

 private:
  struct Value {
    std::string text;
    int line = 0;
  };
  std::string path_;
  std::map<std::string, std::map<std::string, Value>> sections_;
  mutable std::set<std::pair<std::string, std::string>> read_;  // (section, key) asked for
};

}  // namespace rpvio
