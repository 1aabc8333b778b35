#pragma once
#include <cstdint>

namespace servoloop {

// What a real-time call reports instead of throwing.
//   ok         — carry on;
//   error      — this component failed; the manager stops it and reports once;
//   deactivate — the component asks to be stopped cleanly (no error).
enum class ReturnType : std::uint8_t { ok, error, deactivate };

}  // namespace servoloop
