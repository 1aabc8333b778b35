#pragma once
// The keys of a YAML launch file, declared once each with its type and what it
// means (docs/launch_files.md describes them for users). The launch file
// reader checks every map against its schema (an unknown key is an error with
// the file and line) and reads the values with the file's positions in its
// messages.
#include "servoloop/params/schema.hpp"

namespace servoloop::node::launch_keys {

const params::Schema& top();                 // the file's top level
const params::Schema& world();               // world:
const params::Schema& controllerManager();   // controller_manager:
const params::Schema& robot();               // robots: [ ... ] entries
const params::Schema& realtime();            // realtime: (top level or a robot's)
const params::Schema& parameterFile();       // a robot's params: [{file, ns}]
const params::Schema& publication();         // publish: [ ... ] entries
const params::Schema& recording();           // record: [ ... ] entries

}  // namespace servoloop::node::launch_keys
