#pragma once
// How validation errors show a JSON value they did not expect: "a string (\"abc\")", "a number
// (1e+300)", "an array of 2" ... (shared by every JSON file format: scenes, recordings).
#include <nlohmann/json.hpp>

#include <string>

namespace foresight {

std::string json_describe(const nlohmann::json& value);

}  // namespace foresight
