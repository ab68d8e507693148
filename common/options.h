#pragma once
// The one options pattern: an options struct names each of its fields once, in
//
//   template <class Visitor> void fields(Visitor& v) {
//     RPVIO_OPTION(v, max_features);                          // int, double, size_t, bool, string
//     RPVIO_OPTION_CHOICE(v, homography_planes, kHomographyPlanesNames);  // an enum by name
//   }
//
// and gets from it `loadOptions<T>(ini, section)` (the INI key of a field is the field's name;
// keys absent keep the default; a bad value is an InputError naming the file and line) and
// `describeOptions(options)` (`key = value` lines an INI file can be made of). Unknown keys are
// found by IniFile::unreadKeys() once every module has read its section.
#include <Eigen/Core>
#include <cstdint>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/ini_file.h"

#define RPVIO_OPTION(visitor, field) visitor(#field, field)
#define RPVIO_OPTION_CHOICE(visitor, field, names) visitor(#field, field, names)

namespace rpvio {

/// The names an enum option is written as in an INI file.
template <typename Enum>
using OptionNames = std::vector<std::pair<const char*, Enum>>;

/// Shortest decimal text that reads back as the same double ("0.1", not "0.10000000000000001").
std::string exactNumberText(double value);

/// Reads the fields of an options struct from one INI section.
class OptionsLoader {
 public:
  OptionsLoader(const IniFile& ini, std::string section)
      : ini_(ini), section_(std::move(section)) {}

  void operator()(const char* key, double& value);
  void operator()(const char* key, int& value);       // a whole number
  void operator()(const char* key, uint64_t& value);  // a non-negative whole number
  void operator()(const char* key, bool& value);      // true/false, 1/0, yes/no
  void operator()(const char* key, std::string& value);
  void operator()(const char* key, Eigen::Vector3d& value);  // three numbers: x y z
  template <typename Enum>
  void operator()(const char* key, Enum& value, const OptionNames<Enum>& names) {
    if (!ini_.has(section_, key)) return;
    const std::string text = ini_.text(section_, key);
    std::string list;
    for (const auto& [name, option] : names) {
      if (text == name) {
        value = option;
        return;
      }
      list += (list.empty() ? "" : ", ") + std::string(name);
    }
    fail(key, "must be one of " + list + ", not '" + text + "'");
  }
  /// InputError at the key's line (or the section when the key is absent) unless `valid`.
  void require(bool valid, const char* key, const std::string& what) const;

 private:
  [[noreturn]] void fail(const char* key, const std::string& what) const;
  const IniFile& ini_;
  std::string section_;
};

/// Writes the fields of an options struct as `key = value` lines.
class OptionsDescriber {
 public:
  void operator()(const char* key, double value) { line(key, exactNumberText(value)); }
  void operator()(const char* key, int value) { line(key, std::to_string(value)); }
  void operator()(const char* key, uint64_t value) { line(key, std::to_string(value)); }
  void operator()(const char* key, bool value) { line(key, value ? "true" : "false"); }
  void operator()(const char* key, const std::string& value) { line(key, value); }
  void operator()(const char* key, const Eigen::Vector3d& value) {
    line(key, exactNumberText(value.x()) + " " + exactNumberText(value.y()) + " " +
                  exactNumberText(value.z()));
  }
  template <typename Enum>
  void operator()(const char* key, Enum value, const OptionNames<Enum>& names) {
    for (const auto& [name, option] : names)
      if (option == value) line(key, name);
  }
  std::string text() const { return out_.str(); }

 private:
  void line(const char* key, const std::string& value) { out_ << key << " = " << value << "\n"; }
  std::ostringstream out_;
};

/// The options of `section` over `defaults` (Options::validate(loader) runs after, when it has
/// one).
template <typename Options, typename = void>
struct HasValidate : std::false_type {};
template <typename Options>
struct HasValidate<Options, std::void_t<decltype(std::declval<const Options&>().validate(
                                std::declval<const OptionsLoader&>()))>> : std::true_type {};

template <typename Options>
Options loadOptions(const IniFile& ini, const std::string& section, Options defaults = Options()) {
  Options options = std::move(defaults);
  OptionsLoader loader(ini, section);
  options.fields(loader);
  if constexpr (HasValidate<Options>::value) options.validate(loader);
  return options;
}

/// `key = value` lines, one per field, in declaration order.
template <typename Options>
std::string describeOptions(Options options) {
  OptionsDescriber describer;
  options.fields(describer);
  return describer.text();
}

}  // namespace rpvio
