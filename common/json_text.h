#pragma once
// Small helpers for the JSON files the apps write by hand.
#include <string>

namespace rpvio {

/// `s` as a JSON string literal (quotes and backslashes escaped).
std::string jsonString(const std::string& s);

/// The number after `"key":` in a flat JSON text; NaN when the key is absent.
double jsonNumber(const std::string& json, const std::string& key);

}  // namespace rpvio
