// The control_toolbox PID cases of ros_control_semantics.md, case by case,
// plus the `pid` YAML parsing rules and the real-time guarantees.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "alloc_counter.hpp"
#include "log_capture.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/params/parameters_yaml.hpp"

using servoloop::controllers::Pid;

namespace {
constexpr double kTol = 1e-12;

struct Step {
  double error;
  double dt;
  double expected_command;
};

// Feeds errors through computeCommand(e, dt) and checks each command.
void expectCommands(Pid& pid, const std::vector<Step>& steps) {
  for (std::size_t k = 0; k < steps.size(); ++k) {
    SCOPED_TRACE("step " + std::to_string(k) + ", error " + std::to_string(steps[k].error));
    EXPECT_NEAR(pid.computeCommand(steps[k].error, steps[k].dt), steps[k].expected_command, kTol);
  }
}

Pid fromYaml(const std::string& text) {
  Pid pid;
  pid.initFromParams(servoloop::params::parametersFromYaml(YAML::Load(text), "/robot/ctrl/pid"), "robot/ctrl/pid");
  return pid;
}

std::string configErrorMessage(const std::string& text) {
  try {
    fromYaml(text);
  } catch (const servoloop::ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}
}  // namespace

// --- Numeric cases of the reference (dt = 1 unless said) ---------------------

TEST(PidReferenceCases, PidDerivativeAndIntegralTogether) {
  Pid pid(1.0, 1.0, 1.0, 5.0, -5.0);
  expectCommands(pid, {{-0.5, 1.0, -1.5}, {-0.5, 1.0, -1.5}, {-1.0, 1.0, -3.5}});
}

TEST(PidReferenceCases, IntegralOnly) {
  Pid pid(0.0, 1.0, 0.0, 5.0, -5.0);
  expectCommands(pid, {{-0.5, 1.0, -0.5}, {-0.5, 1.0, -1.0}, {0.0, 1.0, -1.0}, {0.0, 1.0, -1.0},
                       {1.0, 1.0, 0.0}});
}

TEST(PidReferenceCases, DerivativeOnlyWithFirstCallKickAndShortStep) {
  Pid pid(0.0, 0.0, 1.0, 0.0, 0.0);
  expectCommands(pid, {{-0.5, 1.0, -0.5}, {-0.5, 1.0, 0.0}, {-0.5, 0.1, 0.0}, {-1.0, 1.0, -0.5},
                       {-0.5, 1.0, 0.5}});
}

TEST(PidReferenceCases, AntiwindupClampsTheIntegralState) {
  Pid pid(0.0, 2.0, 0.0, 1.0, -1.0, true);
  expectCommands(pid, {{-1.0, 1.0, -1.0}, {-1.0, 1.0, -1.0}, {0.5, 1.0, 0.0}, {-1.0, 1.0, -1.0}});
}

TEST(PidReferenceCases, AntiwindupWithNegativeIntegralGainSwapsTheBounds) {
  Pid pid(0.0, -2.5, 0.0, 0.5, -0.2, true);
  expectCommands(pid, {{0.1, 1.0, -0.2}, {0.1, 1.0, -0.2}, {-0.05, 1.0, -0.075}, {0.1, 1.0, -0.2}});
}

TEST(PidReferenceCases, WithoutAntiwindupTheTermIsClampedNotTheState) {
  Pid pid(0.0, 1.0, 0.0, 1.0, -1.0);
  expectCommands(pid, {{-10.03, 1.0, -1.0}, {30.0, 1.0, 1.0}});
  // i_error kept growing: -10.03 + 30 = 19.97 (antiwindup would have held it at ±1).
  double pe = 0.0, ie = 0.0, de = 0.0;
  pid.getCurrentPIDErrors(pe, ie, de);
  EXPECT_NEAR(ie, 19.97, kTol);
  // So it takes an error of -18.97 (i_error 1.0) to bring I just inside the clamp.
  EXPECT_NEAR(pid.computeCommand(-19.47, 1.0), 0.5, kTol);
}

// --- Other computeCommand rules ---------------------------------------------

TEST(Pid, ZeroOrNonFiniteInputsGiveZeroAndLeaveState) {
  Pid pid(2.0, 1.0, 1.0, 10.0, -10.0);
  EXPECT_EQ(pid.computeCommand(1.0, 0.0), 0.0);
  EXPECT_EQ(pid.computeCommand(std::numeric_limits<double>::quiet_NaN(), 1.0), 0.0);
  EXPECT_EQ(pid.computeCommand(std::numeric_limits<double>::infinity(), 1.0), 0.0);
  EXPECT_EQ(pid.computeCommand(1.0, std::numeric_limits<double>::quiet_NaN(), 1.0), 0.0);
  EXPECT_EQ(pid.computeCommand(1.0, 0.0, 0.0), 0.0);
  // State untouched: this is still the first real call (P 2 + I 1 + D kick 1).
  EXPECT_NEAR(pid.computeCommand(1.0, 1.0), 4.0, kTol);
}

TEST(Pid, ExplicitErrorDerivative) {
  Pid pid(1.0, 0.0, 0.5, 0.0, 0.0);
  // P = 2, D = 0.5·(-4) = -2.
  EXPECT_NEAR(pid.computeCommand(2.0, -4.0, 0.01), 0.0, kTol);
  double pe = 0.0, ie = 0.0, de = 0.0;
  pid.getCurrentPIDErrors(pe, ie, de);
  EXPECT_NEAR(pe, 2.0, kTol);
  EXPECT_NEAR(ie, 0.02, kTol);
  EXPECT_NEAR(de, -4.0, kTol);
  EXPECT_NEAR(pid.getCurrentCmd(), 0.0, kTol);
}

TEST(Pid, ResetRestoresTheFirstCallKick) {
  Pid pid(0.0, 0.0, 1.0, 0.0, 0.0);
  EXPECT_NEAR(pid.computeCommand(-0.5, 1.0), -0.5, kTol);
  EXPECT_NEAR(pid.computeCommand(-0.5, 1.0), 0.0, kTol);
  pid.reset();
  EXPECT_NEAR(pid.computeCommand(-0.5, 1.0), -0.5, kTol);
  pid.reset();
  double pe = 1.0, ie = 1.0, de = 1.0;
  pid.getCurrentPIDErrors(pe, ie, de);
  EXPECT_EQ(pe, 0.0);
  EXPECT_EQ(ie, 0.0);
  EXPECT_EQ(de, 0.0);
  EXPECT_EQ(pid.getCurrentCmd(), 0.0);
}

TEST(Pid, NoIntegralActionWithoutClamp) {
  Pid pid = fromYaml("{p: 0.0, i: 100.0}");
  EXPECT_NEAR(pid.computeCommand(3.0, 1.0), 0.0, kTol);
  EXPECT_NEAR(pid.computeCommand(3.0, 1.0), 0.0, kTol);
}

TEST(Pid, GainsSetAndGet) {
  Pid pid;
  pid.setGains(1.0, 2.0, 3.0, 4.0, -5.0, true);
  double p, i, d, i_max, i_min;
  bool antiwindup = false;
  pid.getGains(p, i, d, i_max, i_min, antiwindup);
  EXPECT_EQ(p, 1.0);
  EXPECT_EQ(i, 2.0);
  EXPECT_EQ(d, 3.0);
  EXPECT_EQ(i_max, 4.0);
  EXPECT_EQ(i_min, -5.0);
  EXPECT_TRUE(antiwindup);
  // The new gains apply from the next computeCommand: P = 1·2.
  EXPECT_EQ(pid.getActiveGains().p_gain, 0.0);
  EXPECT_NEAR(pid.computeCommand(2.0, 0.0, 1.0), 2.0 + 4.0, kTol);  // I = 2·2 = 4 (inside ±)
  EXPECT_EQ(pid.getActiveGains().p_gain, 1.0);
}

TEST(Pid, CopyKeepsGainsAndState) {
  Pid pid(1.0, 1.0, 1.0, 5.0, -5.0);
  pid.computeCommand(-0.5, 1.0);
  Pid copy(pid);
  // The second case-1 step from both.
  EXPECT_NEAR(copy.computeCommand(-0.5, 1.0), -1.5, kTol);
  EXPECT_NEAR(pid.computeCommand(-0.5, 1.0), -1.5, kTol);
  std::vector<Pid> pids(3, pid);
  EXPECT_NEAR(pids[2].computeCommand(-1.0, 1.0), -3.5, kTol);
}

// --- initFromParams ----------------------------------------------------------

TEST(PidParams, SeedControllerGains) {
  Pid pid = fromYaml("{p: 10.0, i: 10.0, d: 10.0, i_clamp_min: -10.0, i_clamp_max: 10.0}");
  const Pid::Gains gains = pid.getGains();
  EXPECT_EQ(gains.p_gain, 10.0);
  EXPECT_EQ(gains.i_gain, 10.0);
  EXPECT_EQ(gains.d_gain, 10.0);
  EXPECT_EQ(gains.i_max, 10.0);
  EXPECT_EQ(gains.i_min, -10.0);
  EXPECT_FALSE(gains.antiwindup);
}

TEST(PidParams, DefaultsForOptionalKeys) {
  const Pid::Gains gains = fromYaml("{p: 3}").getGains();
  EXPECT_EQ(gains.p_gain, 3.0);
  EXPECT_EQ(gains.i_gain, 0.0);
  EXPECT_EQ(gains.d_gain, 0.0);
  EXPECT_EQ(gains.i_max, 0.0);
  EXPECT_EQ(gains.i_min, 0.0);
  EXPECT_FALSE(gains.antiwindup);
}

TEST(PidParams, IClampIsSymmetricWhateverItsSign) {
  for (const char* text : {"{p: 1, i_clamp: 3}", "{p: 1, i_clamp: -3}"}) {
    SCOPED_TRACE(text);
    const Pid::Gains gains = fromYaml(text).getGains();
    EXPECT_EQ(gains.i_max, 3.0);
    EXPECT_EQ(gains.i_min, -3.0);
  }
}

TEST(PidParams, OneSidedClampsOverrideAndForceTheirSign) {
  Pid::Gains gains = fromYaml("{p: 1, i_clamp: 5, i_clamp_max: -1}").getGains();
  EXPECT_EQ(gains.i_max, 1.0);
  EXPECT_EQ(gains.i_min, -5.0);
  gains = fromYaml("{p: 1, i_clamp: 5, i_clamp_min: 2}").getGains();
  EXPECT_EQ(gains.i_max, 5.0);
  EXPECT_EQ(gains.i_min, -2.0);
  gains = fromYaml("{p: 1, i_clamp_min: 2}").getGains();
  EXPECT_EQ(gains.i_max, 0.0);
  EXPECT_EQ(gains.i_min, -2.0);
}

TEST(PidParams, Antiwindup) {
  EXPECT_TRUE(fromYaml("{p: 1, antiwindup: true}").getGains().antiwindup);
}

// ros_control ignores a misspelt key and accepts a negative gain without a
// word; here each is one warning naming the key, and the gains still load.
TEST(PidParams, UnknownKeysAndNegativeGainsAreOneWarningEach) {
  servoloop::test::LogCapture log;
  const Pid pid = fromYaml("{p: -2.0, i: 0.5, dd: 3.0, publish_state: true}");
  EXPECT_EQ(pid.getGains().p_gain, -2.0);
  EXPECT_EQ(pid.getGains().d_gain, 0.0) << "the misspelt d gain stays 0";
  EXPECT_EQ(log.count("robot/ctrl/pid: unknown key 'dd' is ignored; did you mean 'd'?"), 1u) << log.text();
  EXPECT_EQ(log.count("robot/ctrl/pid/p: the gain -2 is negative"), 1u) << log.text();
  EXPECT_EQ(log.count("unknown key 'publish_state'"), 0u) << "a key ros_control reads is not unknown: " << log.text();
  EXPECT_EQ(log.count("/i: the gain"), 0u) << log.text();
}

TEST(PidParams, InitResetsState) {
  Pid pid(0.0, 0.0, 1.0, 0.0, 0.0);
  pid.computeCommand(-0.5, 1.0);
  pid.initFromParams(servoloop::params::parametersFromYaml(YAML::Load("{p: 0, d: 1}"), "/robot/ctrl/pid"), "robot/ctrl/pid");
  EXPECT_NEAR(pid.computeCommand(-0.5, 1.0), -0.5, kTol);  // the kick again
}

TEST(PidParams, MissingPGainNamesTheLocation) {
  const std::string message = configErrorMessage("{i: 1.0, d: 2.0}");
  EXPECT_NE(message.find("No p gain specified"), std::string::npos) << message;
  EXPECT_NE(message.find("robot/ctrl/pid"), std::string::npos) << message;
  // An absent pid map is the same mistake.
  Pid pid;
  try {
    pid.initFromParams(servoloop::params::Parameters(), "robot/ctrl/pid");
    FAIL() << "expected ConfigError";
  } catch (const servoloop::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("No p gain specified"), std::string::npos) << e.what();
  }
}

TEST(PidParams, WrongTypesNameKeyAndExpectedType) {
  std::string message = configErrorMessage("{p: fast}");
  EXPECT_NE(message.find("robot/ctrl/pid/p"), std::string::npos) << message;
  EXPECT_NE(message.find("a number"), std::string::npos) << message;
  EXPECT_NE(message.find("'fast'"), std::string::npos) << message;

  message = configErrorMessage("{p: 1, i_clamp: [1, 2]}");
  EXPECT_NE(message.find("robot/ctrl/pid/i_clamp"), std::string::npos) << message;
  EXPECT_NE(message.find("a list"), std::string::npos) << message;

  message = configErrorMessage("{p: 1, antiwindup: 2}");
  EXPECT_NE(message.find("robot/ctrl/pid/antiwindup"), std::string::npos) << message;
  EXPECT_NE(message.find("boolean"), std::string::npos) << message;

  message = configErrorMessage("10.0");
  EXPECT_NE(message.find("robot/ctrl/pid: expected a map"), std::string::npos) << message;
}

// --- Real-time guarantees ----------------------------------------------------

TEST(PidRealTime, ComputeCommandDoesNotAllocate) {
  Pid pid(1.0, 1.0, 1.0, 5.0, -5.0, true);
  servoloop::testing::AllocationCounter counter;
  double sum = 0.0;
  for (int k = 0; k < 1000; ++k) {
    sum += pid.computeCommand(std::sin(0.01 * k), 0.001);
    sum += pid.computeCommand(0.1, -0.2, 0.001);
    if (k % 100 == 0) pid.reset();
  }
  pid.setGains(2.0, 0.0, 0.0, 0.0, 0.0);
  sum += pid.computeCommand(1.0, 0.001);
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_TRUE(std::isfinite(sum));
}

// Gains written from another thread are never seen half-written: every set
// written has p = i = d = i_max = -i_min = x and antiwindup = (x is odd).
TEST(PidRealTime, GainsFromAnotherThreadArriveWhole) {
  Pid pid(0.0, 0.0, 0.0, 0.0, 0.0);
  std::atomic<bool> stop{false};
  std::atomic<int> writes{0};
  std::atomic<int> last_written{0};
  std::thread writer([&] {
    for (int x = 1; !stop.load(); x = x % 1000 + 1) {
      pid.setGains(x, x, x, x, -x, x % 2 == 1);
      last_written.store(x);
      writes.fetch_add(1);
      std::this_thread::yield();  // a service thread sets gains now and then, not back to back
    }
  });
  int torn = 0;
  // At least 200,000 reads, and on until the writer has written 1,000 sets
  // (on a loaded machine the writer thread may start late).
  for (int k = 0; k < 200000 || writes.load() < 1000; ++k) {
    pid.computeCommand(1.0, 0.0, 1.0);
    const Pid::Gains& active = pid.getActiveGains();
    const Pid::Gains seen = pid.getGains();
    for (const Pid::Gains* g : {&active, &seen}) {
      const bool whole = g->i_gain == g->p_gain && g->d_gain == g->p_gain && g->i_max == g->p_gain &&
                         g->i_min == -g->p_gain &&
                         (g->p_gain == 0.0 || g->antiwindup == (static_cast<int>(g->p_gain) % 2 == 1));
      torn += whole ? 0 : 1;
    }
  }
  stop = true;
  writer.join();
  EXPECT_EQ(torn, 0);
  // Once the writer is done, the next computeCommand takes its last set.
  pid.computeCommand(1.0, 0.0, 1.0);
  EXPECT_EQ(pid.getActiveGains().p_gain, static_cast<double>(last_written.load()));
  EXPECT_GT(pid.getActiveGains().p_gain, 0.0);
}
