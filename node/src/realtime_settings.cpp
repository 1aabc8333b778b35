#include "servoloop/node/realtime_settings.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "servoloop/core/logging.hpp"

namespace servoloop::node {
namespace {

std::string errnoName(int error) {
  switch (error) {
    case EPERM: return "EPERM";
    case EINVAL: return "EINVAL";
    case ENOMEM: return "ENOMEM";
    case EAGAIN: return "EAGAIN";
    default: return fmt::format("errno {}", error);
  }
}

std::string cpuList(const std::vector<int>& cpus) {
  std::string text;
  for (const int cpu : cpus) text += (text.empty() ? "" : ", ") + std::to_string(cpu);
  return "[" + text + "]";
}

// Writes to every page of a stack buffer so the pages exist before the loop runs.
__attribute__((noinline)) void touchStack(std::size_t bytes) {
  if (bytes == 0) return;
  volatile char* buffer = static_cast<volatile char*>(__builtin_alloca(bytes));
  const long page = sysconf(_SC_PAGESIZE) > 0 ? sysconf(_SC_PAGESIZE) : 4096;
  for (std::size_t i = 0; i < bytes; i += static_cast<std::size_t>(page)) buffer[i] = 0;
}

}  // namespace

RealtimeSettingsOutcome applyRealtimeSettings(const RealtimeSettings& settings, const std::string& who,
                                              std::size_t prefault_stack_bytes) {
  RealtimeSettingsOutcome outcome;
  const auto warn = [&](std::string text) {
    logger().warn("{}", text);
    outcome.warnings.push_back(std::move(text));
  };

  if (settings.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      outcome.memory_locked = true;
    } else {
      const int error = errno;
      warn(fmt::format("{}: realtime.lock_memory: mlockall failed ({}: {}); its memory may be paged out. Fix: raise "
                       "the locked-memory limit (`ulimit -l unlimited`, or '<user> - memlock unlimited' in "
                       "/etc/security/limits.conf, then log in again) or give the program CAP_IPC_LOCK",
                       who, errnoName(error), std::strerror(error)));
    }
  }

  if (!settings.cpu_affinity.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (const int cpu : settings.cpu_affinity) CPU_SET(cpu, &set);
    const int error = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
    if (error == 0) {
      outcome.affinity_applied = true;
    } else {
      const long online = sysconf(_SC_NPROCESSORS_ONLN);
      warn(fmt::format("{}: realtime.cpu_affinity {}: not applied ({}: {}){}; the loop thread runs on any CPU. Fix: "
                       "name CPUs this machine has and the process may use (`nproc`, `taskset -p $$`)",
                       who, cpuList(settings.cpu_affinity), errnoName(error), std::strerror(error),
                       error == EINVAL ? fmt::format(": no such CPU (this machine has {} online: 0 to {})", online,
                                                     online - 1)
                                       : std::string()));
    }
  }

  if (settings.priority) {
    sched_param param{};
    param.sched_priority = *settings.priority;
    const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (error == 0) {
      outcome.priority_applied = true;
    } else {
      warn(fmt::format("{}: realtime.priority {}: SCHED_FIFO not applied ({}: {}); the loop thread runs with the "
                       "normal scheduler. Fix: allow real-time priorities for the user ('<user> - rtprio 99' in "
                       "/etc/security/limits.conf, then log in again) or give the program CAP_SYS_NICE "
                       "(`sudo setcap cap_sys_nice+ep $(which servoloop)`)",
                       who, *settings.priority, errnoName(error), std::strerror(error)));
    }
  }

  touchStack(prefault_stack_bytes);
  if (outcome.priority_applied || outcome.affinity_applied || outcome.memory_locked) {
    logger().info("{}: loop thread{}{}{}", who,
                  outcome.priority_applied ? fmt::format(" SCHED_FIFO priority {}", *settings.priority) : "",
                  outcome.affinity_applied ? " on CPUs " + cpuList(settings.cpu_affinity) : "",
                  outcome.memory_locked ? ", memory locked" : "");
  }
  return outcome;
}

}  // namespace servoloop::node
