// JSON text helpers for the places that write JSON by hand (reports,
// GeoJSON, error bodies) rather than through Protobuf's JSON mapping.
#pragma once

#include <string>
#include <string_view>

namespace seaplan {

// `s` as a JSON string literal, quotes included: '"' and '\' escaped, \n
// \r \t by name, other control characters as \u00XX; other bytes (UTF-8)
// as they are.
std::string JsonString(std::string_view s);

}  // namespace seaplan
