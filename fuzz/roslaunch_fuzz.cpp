// The ROS launch-file (roslaunch XML) reader on arbitrary text, through a file
// of its own as the command line reads one.
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "fuzz_common.hpp"
#include "servoloop/node/roslaunch_xml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("servoloop-fuzz-" + std::to_string(::getpid()) + ".launch");
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                static_cast<std::streamsize>(size));
  return servoloop::fuzz::refusalsAllowed([&] { servoloop::node::loadRoslaunchFile(file, {{"fuzz", "1"}}); });
}
