#pragma once
// Real-time settings of a robot's loop thread, from the launch file:
//
//   realtime: {priority: 80, cpu_affinity: [1], lock_memory: true}
//
// (top level, for every robot; or in a robot's entry, for that robot).
// Applied on the loop thread before its first cycle, each when the system
// permits it; a setting that cannot be applied leaves one warning naming the
// setting, the reason (EPERM, no such CPU) and the fix, and the robot runs
// without it. Then the thread's stack is touched (pre-faulted) so that the
// cycles do not page-fault on it.
#include <optional>
#include <string>
#include <vector>

namespace servoloop::node {

struct RealtimeSettings {
  std::optional<int> priority;  // SCHED_FIFO priority 1..99; unset: the normal scheduler
  std::vector<int> cpu_affinity;  // CPUs the loop thread may run on; empty: any
  bool lock_memory = false;       // mlockall(MCL_CURRENT | MCL_FUTURE): no page ever swapped out
  bool empty() const { return !priority && cpu_affinity.empty() && !lock_memory; }
};

// What applyRealtimeSettings did: one line per setting not applied.
struct RealtimeSettingsOutcome {
  bool priority_applied = false;
  bool affinity_applied = false;
  bool memory_locked = false;
  std::vector<std::string> warnings;  // each also logged
};

// Non-real-time, on the thread to configure (the loop thread, before its
// first cycle). `who` names the robot in warnings ("robot '/arm'"). Touches
// `prefault_stack_bytes` of the calling thread's stack afterwards.
RealtimeSettingsOutcome applyRealtimeSettings(const RealtimeSettings& settings, const std::string& who,
                                              std::size_t prefault_stack_bytes = 256 * 1024);

}  // namespace servoloop::node
