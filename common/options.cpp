#include "common/options.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "common/input_error.h"

namespace rpvio {

std::string exactNumberText(double value) {
  char text[32];
  if (value == std::floor(value) && std::abs(value) < 1e15) {  // whole: no exponent
    std::snprintf(text, sizeof text, "%.0f", value);
    return text;
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

void OptionsLoader::fail(const char* key, const std::string& what) const {
  const int line = ini_.line(section_, key);
  throw InputError(ini_.path(), line ? "line " + std::to_string(line) : "[" + section_ + "]",
                   std::string(key) + " " + what);
}

void OptionsLoader::require(bool valid, const char* key, const std::string& what) const {
  if (!valid) fail(key, what);
}

void OptionsLoader::operator()(const char* key, double& value) {
  if (ini_.has(section_, key)) value = ini_.number(section_, key);
}

void OptionsLoader::operator()(const char* key, int& value) {
  if (!ini_.has(section_, key)) return;
  const double v = ini_.number(section_, key);
  if (v != std::floor(v) || std::abs(v) > 1e9) fail(key, "must be a whole number");
  value = static_cast<int>(v);
}

void OptionsLoader::operator()(const char* key, uint64_t& value) {
  if (!ini_.has(section_, key)) return;
  const double v = ini_.number(section_, key);
  if (v < 0 || v != std::floor(v) || v > 1e15) fail(key, "must be a non-negative whole number");
  value = static_cast<uint64_t>(v);
}

void OptionsLoader::operator()(const char* key, bool& value) {
  value = ini_.flagOr(section_, key, value);
}

void OptionsLoader::operator()(const char* key, std::string& value) {
  value = ini_.textOr(section_, key, value);
}

void OptionsLoader::operator()(const char* key, Eigen::Vector3d& value) {
  if (!ini_.has(section_, key)) return;
  const std::vector<double> v = ini_.numbers(section_, key, 3);
  value = Eigen::Vector3d(v[0], v[1], v[2]);
}

}  // namespace rpvio
