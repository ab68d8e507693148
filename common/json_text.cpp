#include "common/json_text.h"

#include "common/sensor_types.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

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

std::string JsonObject::formatNumber(double value) const {
  if (!std::isfinite(value)) return "null";
  std::ostringstream text;
  text.precision(digits_);
  text << value;
  return text.str();
}

JsonObject& JsonObject::add(const std::string& key, std::string value) {
  members_.push_back({key, std::move(value), {}, false});
  return *this;
}

JsonObject& JsonObject::number(const std::string& key, double value) {
  return add(key, formatNumber(value));
}

JsonObject& JsonObject::stamp(const std::string& key, double seconds) {
  return add(key, std::isfinite(seconds) ? stampText(seconds) : "null");
}

JsonObject& JsonObject::integer(const std::string& key, long long value) {
  return add(key, std::to_string(value));
}

JsonObject& JsonObject::text(const std::string& key, const std::string& value) {
  return add(key, jsonString(value));
}

JsonObject& JsonObject::flag(const std::string& key, bool value) {
  return add(key, value ? "true" : "false");
}

JsonObject& JsonObject::null(const std::string& key) { return add(key, "null"); }

JsonObject& JsonObject::numbers(const std::string& key, const std::vector<double>& values) {
  std::string list = "[";
  for (size_t k = 0; k < values.size(); ++k) list += (k ? ", " : "") + formatNumber(values[k]);
  return add(key, list + "]");
}

JsonObject& JsonObject::object(const std::string& key, const JsonObject& value) {
  return add(key, value.oneLine());
}

JsonObject& JsonObject::objects(const std::string& key, const std::vector<JsonObject>& values) {
  Member m{key, "", {}, true};
  for (const JsonObject& v : values) m.elements.push_back(v.oneLine());
  members_.push_back(std::move(m));
  return *this;
}

std::string JsonObject::oneLine() const {
  std::string out = "{";
  for (size_t k = 0; k < members_.size(); ++k) {
    const Member& m = members_[k];
    out += (k ? ", " : "") + jsonString(m.key) + ": ";
    if (!m.is_object_array) {
      out += m.value;
      continue;
    }
    out += "[";
    for (size_t e = 0; e < m.elements.size(); ++e) out += (e ? ", " : "") + m.elements[e];
    out += "]";
  }
  return out + "}";
}

std::string JsonObject::str() const {
  if (members_.empty()) return "{}\n";
  std::string out = "{";
  for (size_t k = 0; k < members_.size(); ++k) {
    const Member& m = members_[k];
    out += std::string(k ? "," : "") + "\n  " + jsonString(m.key) + ": ";
    if (!m.is_object_array) {
      out += m.value;
    } else if (m.elements.empty()) {
      out += "[]";
    } else {
      out += "[";
      for (size_t e = 0; e < m.elements.size(); ++e)
        out += std::string(e ? "," : "") + "\n    " + m.elements[e];
      out += "\n  ]";
    }
  }
  return out + "\n}\n";
}

double jsonNumber(const std::string& json, const std::string& key) {
  const std::string quoted = "\"" + key + "\":";
  const auto at = json.find(quoted);
  if (at == std::string::npos) return std::numeric_limits<double>::quiet_NaN();
  const char* begin = json.c_str() + at + quoted.size();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  return end == begin ? std::numeric_limits<double>::quiet_NaN() : value;
}

}  // namespace rpvio
