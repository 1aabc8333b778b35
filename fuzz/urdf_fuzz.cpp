// The URDF loader, the transmission parser and the <gazebo> sensors reader
// on arbitrary text.
#include "fuzz_common.hpp"
#include "servoloop/description/gazebo_sensors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/transmissions/transmission_parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string urdf = servoloop::fuzz::text(data, size);
  return servoloop::fuzz::refusalsAllowed([&] {
    const auto model = servoloop::parseRobotModel(urdf, "fuzz.urdf");
    servoloop::transmissions::parseTransmissions(urdf, "fuzz.urdf");
    servoloop::readGazeboSensors(urdf, *model, "fuzz.urdf");
  });
}
