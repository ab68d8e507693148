#pragma once
// Small helpers for the JSON files the apps write by hand.
#include <string>

namespace rpvio {

/// `s` as a JSON string literal (quotes and backslashes escaped).
std::string jsonString(const std::string& s);

}  // namespace rpvio
