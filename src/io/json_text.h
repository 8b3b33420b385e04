// The text of the JSON files relight writes (scene.json, rig.json,
// analysis.json, ...): indented, and each number that was a float written as
// the shortest decimal that reads back as that float — a colour typed as
// 0.85 is saved as 0.85, not as the double nearest the float,
// 0.8500000238418579.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace relight {

std::string json_text(const nlohmann::json& j);

}  // namespace relight
