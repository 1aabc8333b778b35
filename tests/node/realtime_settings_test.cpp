// The loop thread's real-time settings: each one is applied, or leaves one
// warning naming the setting, the reason and the fix — never silently
// dropped. Whether SCHED_FIFO and mlockall are permitted depends on the
// machine (user limits, capabilities), so those tests accept either outcome
// and check it against what the system reports.
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/realtime_settings.hpp"

namespace servoloop::node {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Runs `body` on a fresh thread (so the test's own thread keeps its settings).
template <class F>
void onThread(F body) {
  std::thread thread(body);
  thread.join();
}

TEST(RealtimeSettings, NothingAskedNothingDone) {
  onThread([] {
    const RealtimeSettingsOutcome outcome = applyRealtimeSettings({}, "robot '/r'");
    EXPECT_TRUE(outcome.warnings.empty());
    EXPECT_FALSE(outcome.priority_applied || outcome.affinity_applied || outcome.memory_locked);
  });
}

TEST(RealtimeSettings, CpuAffinityPinsTheThread) {
  onThread([] {
    cpu_set_t allowed;
    ASSERT_EQ(sched_getaffinity(0, sizeof(allowed), &allowed), 0);
    int cpu = 0;
    while (!CPU_ISSET(cpu, &allowed)) ++cpu;  // a CPU this process may use
    RealtimeSettings settings;
    settings.cpu_affinity = {cpu};
    const RealtimeSettingsOutcome outcome = applyRealtimeSettings(settings, "robot '/r'");
    EXPECT_TRUE(outcome.affinity_applied);
    EXPECT_TRUE(outcome.warnings.empty());
    cpu_set_t now;
    ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof(now), &now), 0);
    EXPECT_EQ(CPU_COUNT(&now), 1);
    EXPECT_TRUE(CPU_ISSET(cpu, &now));
  });
}

TEST(RealtimeSettings, ACpuTheMachineLacksIsOneWarning) {
  onThread([] {
    RealtimeSettings settings;
    settings.cpu_affinity = {1000};
    const RealtimeSettingsOutcome outcome = applyRealtimeSettings(settings, "robot '/r'");
    EXPECT_FALSE(outcome.affinity_applied);
    ASSERT_EQ(outcome.warnings.size(), 1u);
    EXPECT_TRUE(contains(outcome.warnings[0], "robot '/r': realtime.cpu_affinity [1000]")) << outcome.warnings[0];
    EXPECT_TRUE(contains(outcome.warnings[0], "no such CPU")) << outcome.warnings[0];
  });
}

TEST(RealtimeSettings, PriorityIsAppliedOrWarnedAbout) {
  onThread([] {
    RealtimeSettings settings;
    settings.priority = 10;
    const RealtimeSettingsOutcome outcome = applyRealtimeSettings(settings, "robot '/r'");
    int policy = -1;
    sched_param param{};
    ASSERT_EQ(pthread_getschedparam(pthread_self(), &policy, &param), 0);
    if (outcome.priority_applied) {
      EXPECT_EQ(policy, SCHED_FIFO);
      EXPECT_EQ(param.sched_priority, 10);
      EXPECT_TRUE(outcome.warnings.empty());
    } else {
      EXPECT_NE(policy, SCHED_FIFO);
      ASSERT_EQ(outcome.warnings.size(), 1u);
      EXPECT_TRUE(contains(outcome.warnings[0], "realtime.priority 10: SCHED_FIFO not applied (EPERM"))
          << outcome.warnings[0];
      EXPECT_TRUE(contains(outcome.warnings[0], "CAP_SYS_NICE")) << outcome.warnings[0];
      EXPECT_TRUE(contains(outcome.warnings[0], "rtprio")) << outcome.warnings[0];
    }
  });
}

// A sanitizer build maps terabytes of shadow memory that mlockall would try
// to fault in: the test runs in plain builds only.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

TEST(RealtimeSettings, LockedMemoryIsAppliedOrWarnedAbout) {
  if (kSanitized) GTEST_SKIP() << "mlockall of a sanitizer's shadow memory";
  onThread([] {
    RealtimeSettings settings;
    settings.lock_memory = true;
    const RealtimeSettingsOutcome outcome = applyRealtimeSettings(settings, "robot '/r'");
    if (outcome.memory_locked) {
      EXPECT_TRUE(outcome.warnings.empty());
      EXPECT_EQ(munlockall(), 0);
    } else {
      ASSERT_EQ(outcome.warnings.size(), 1u);
      EXPECT_TRUE(contains(outcome.warnings[0], "realtime.lock_memory: mlockall failed")) << outcome.warnings[0];
      EXPECT_TRUE(contains(outcome.warnings[0], "memlock")) << outcome.warnings[0];
    }
  });
}

TEST(RealtimeSettings, LaunchFileKeysAtTheTopAndPerRobot) {
  const LaunchFile launch = parseLaunchFile(R"(
realtime: {priority: 80, cpu_affinity: [1, 0], lock_memory: true}
robots:
  - urdf: minimal_robot_description.urdf
    realtime: {cpu_affinity: 1}
)",
                                            "rt.launch.yaml", SERVOLOOP_SEED_DIR);
  ASSERT_TRUE(launch.realtime.priority.has_value());
  EXPECT_EQ(*launch.realtime.priority, 80);
  EXPECT_EQ(launch.realtime.cpu_affinity, (std::vector<int>{1, 0}));
  EXPECT_TRUE(launch.realtime.lock_memory);
  ASSERT_TRUE(launch.robots[0].realtime.has_value());
  EXPECT_EQ(launch.robots[0].realtime->cpu_affinity, std::vector<int>{1});
  EXPECT_FALSE(launch.robots[0].realtime->priority.has_value());
}

TEST(RealtimeSettings, BadLaunchFileValuesNameTheKey) {
  const auto error = [](const std::string& yaml) {
    try {
      parseLaunchFile(yaml, "rt.launch.yaml", SERVOLOOP_SEED_DIR);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_TRUE(contains(error("realtime: {priority: 150}"), "realtime.priority: expected a SCHED_FIFO priority, a whole "
                                                           "number from 1 to 99, got 150"));
  EXPECT_TRUE(contains(error("realtime: {priority: 8.5}"), "realtime.priority"));
  EXPECT_TRUE(contains(error("realtime: {cpu_affinity: [-1]}"), "realtime.cpu_affinity[0]"));
  EXPECT_TRUE(contains(error("realtime: {cpu_affinity: []}"), "realtime.cpu_affinity: expected a list of CPU numbers"));
  EXPECT_TRUE(contains(error("realtime: {lock_memory: maybe}"), "realtime.lock_memory"));
  EXPECT_TRUE(contains(error("realtime: {nice: 5}"), "unknown key 'nice'"));
}

}  // namespace
}  // namespace servoloop::node
