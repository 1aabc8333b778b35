// The xacro expander on arbitrary text (its limits keep every input bounded).
#include "fuzz_common.hpp"
#include "servoloop/description/xacro.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xacro = servoloop::fuzz::text(data, size);
  return servoloop::fuzz::refusalsAllowed([&] { servoloop::expandXacro(xacro, "/nonexistent/fuzz.urdf.xacro"); });
}
