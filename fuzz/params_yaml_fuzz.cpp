// The parameter store's YAML loader, then a full dump (which walks every value).
#include "fuzz_common.hpp"
#include "servoloop/params/parameter_store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string yaml = servoloop::fuzz::text(data, size);
  return servoloop::fuzz::refusalsAllowed([&] {
    servoloop::params::ParameterStore store;
    store.loadString(yaml, "fuzz.yaml", "/robot");
    store.dump("/");
  });
}
