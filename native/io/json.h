// JSON through nlohmann-json (Debian nlohmann-json3-dev). Objects keep their
// keys in insertion order, so a report reads top to bottom as it is built.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace polycube {

using Json = nlohmann::ordered_json;

// The text of json: indent < 0 puts it on one line. Non-finite numbers become
// null (JSON has no NaN); bytes that are not UTF-8 (a path, say) become U+FFFD
// rather than an exception.
inline std::string json_text(const Json& json, int indent = 2) {
  return json.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace polycube
