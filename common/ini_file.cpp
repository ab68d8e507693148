#include "common/ini_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/input_error.h"
#include "common/input_file.h"
#include "common/text_table.h"

namespace rpvio {
namespace {

std::string lineRef(int line) { return "line " + std::to_string(line); }

}  // namespace

IniFile::IniFile(const std::string& path) : path_(path) {
  std::ifstream in = openInputFile(path);
  std::string section, raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::string s = trim(raw.substr(0, raw.find_first_of(";#")));
    if (s.empty()) continue;
    if (s.front() == '[') {
      if (s.back() != ']') throw InputError(path, lineRef(line), "bad section header");
      section = trim(s.substr(1, s.size() - 2));
      continue;
    }
    const auto eq = s.find('=');
    if (eq == std::string::npos || section.empty())
      throw InputError(path, lineRef(line), "expected 'key = value' inside a [section]");
    const std::string key = trim(s.substr(0, eq));
    if (sections_[section].count(key))
      throw InputError(path, lineRef(line),
                       "'" + key + "' given twice in [" + section + "] (first on line " +
                           std::to_string(sections_[section][key].line) + ")");
    sections_[section][key] = {trim(s.substr(eq + 1)), line};
  }
}

bool IniFile::has(const std::string& section, const std::string& key) const {
  read_.emplace(section, key);
  const auto s = sections_.find(section);
  return s != sections_.end() && s->second.count(key);
}

bool IniFile::sectionAskedFor(const std::string& section) const {
  const auto it = read_.lower_bound({section, ""});
  return it != read_.end() && it->first == section;
}

std::vector<IniFile::KeyRef> IniFile::unreadKeys() const {
  std::vector<KeyRef> unread;
  for (const auto& [section, keys] : sections_)
    for (const auto& [key, value] : keys)
      if (!read_.count({section, key})) unread.push_back({section, key, value.line});
  std::sort(unread.begin(), unread.end(),
            [](const KeyRef& a, const KeyRef& b) { return a.line < b.line; });
  return unread;
}

std::string IniFile::text(const std::string& section, const std::string& key) const {
  if (!has(section, key)) throw InputError(path_, "[" + section + "]", "missing key '" + key + "'");
  return sections_.at(section).at(key).text;
}

std::string IniFile::textOr(const std::string& section, const std::string& key,
                            const std::string& fallback) const {
  return has(section, key) ? text(section, key) : fallback;
}

int IniFile::line(const std::string& section, const std::string& key) const {
  return has(section, key) ? sections_.at(section).at(key).line : 0;
}

std::vector<double> IniFile::numbers(const std::string& section, const std::string& key,
                                     size_t count) const {
  std::istringstream ss(text(section, key));
  const int at = line(section, key);
  std::vector<double> out;
  for (std::string token; ss >> token;) {
    char* end = nullptr;
    const double x = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size() || !std::isfinite(x))  // also a NUL inside the token
      throw InputError(path_, lineRef(at), "'" + key + "': not a finite number: " + token);
    out.push_back(x);
  }
  if (out.size() != count)
    throw InputError(path_, lineRef(at),
                     "'" + key + "' needs " + std::to_string(count) + " number(s)");
  return out;
}

double IniFile::number(const std::string& section, const std::string& key) const {
  return numbers(section, key, 1)[0];
}

double IniFile::numberOr(const std::string& section, const std::string& key,
                         double fallback) const {
  return has(section, key) ? number(section, key) : fallback;
}

bool IniFile::flagOr(const std::string& section, const std::string& key, bool fallback) const {
  if (!has(section, key)) return fallback;
  const std::string v = text(section, key);
  if (v == "true" || v == "1" || v == "yes") return true;
  if (v == "false" || v == "0" || v == "no") return false;
  throw InputError(path_, lineRef(line(section, key)), "'" + key + "' must be true or false");
}

}  // namespace rpvio
