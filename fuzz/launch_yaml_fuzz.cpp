// The YAML launch-file reader on arbitrary text.
#include "fuzz_common.hpp"
#include "servoloop/node/launch_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string yaml = servoloop::fuzz::text(data, size);
  return servoloop::fuzz::refusalsAllowed(
      [&] { servoloop::node::parseLaunchFile(yaml, "fuzz.launch.yaml", "/nonexistent"); });
}
