#pragma once
// Fields of an IPC request that several groups of operations read.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace servoloop::node {

// A list of strings, empty when the field is absent or null. Throws
// servoloop::Error naming the field (and the entry) for anything else.
std::vector<std::string> stringList(const nlohmann::json& request, const char* field);

}  // namespace servoloop::node
