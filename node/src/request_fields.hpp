#pragma once
// What several groups of a node's IPC operations share: the fields of a
// request they read, and a manager service's refusal as the request's error.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::node {

// Throws servoloop::Error with the service's message when it failed.
inline void throwIfFailed(const controller_manager::ServiceResult& result) {
  if (!result) throw Error(result.message);
}

// A list of strings, empty when the field is absent or null. Throws
// servoloop::Error naming the field (and the entry) for anything else.
std::vector<std::string> stringList(const nlohmann::json& request, const char* field);

}  // namespace servoloop::node
