// The node's request check on arbitrary lines: it never throws, and what it
// accepts is an object with a string "op".
#include <cstdlib>

#include "fuzz_common.hpp"
#include "servoloop/ipc/ipc_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string line = servoloop::fuzz::text(data, size);
  const servoloop::ipc::IpcRequestCheck checked = servoloop::ipc::parseIpcRequest(line);
  if (checked.ok && !(checked.request.is_object() && checked.request.at("op").is_string())) std::abort();
  if (!checked.ok) servoloop::ipc::encodeIpcLine(checked.error);
  return 0;
}
