#include "common/json_text.h"

#include <cstdio>
#include <cstdlib>
#include <limits>

namespace rpvio {

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned char>(c));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

JsonObject& JsonObject::raw(const std::string& key, const std::string& value) {
  out_ << (empty_ ? "{\n  " : ",\n  ") << jsonString(key) << ": " << value;
  empty_ = false;
  return *this;
}

JsonObject& JsonObject::number(const std::string& key, double value) {
  std::ostringstream text;
  text << value;
  return raw(key, text.str());
}

JsonObject& JsonObject::text(const std::string& key, const std::string& value) {
  return raw(key, jsonString(value));
}

JsonObject& JsonObject::flag(const std::string& key, bool value) {
  return raw(key, value ? "true" : "false");
}

double jsonNumber(const std::string& json, const std::string& key) {
  const std::string quoted = "\"" + key + "\":";
  const auto at = json.find(quoted);
  if (at == std::string::npos) return std::numeric_limits<double>::quiet_NaN();
  return std::strtod(json.c_str() + at + quoted.size(), nullptr);
}

}  // namespace rpvio
