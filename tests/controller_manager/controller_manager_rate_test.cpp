// Fixed-rate scheduling: a controller's update_rate must divide the manager's;
// otherwise the nearest achievable rate is used with a warning. Each update
// gets the true control time since the controller's previous update.
#include <gtest/gtest.h>

#include <chrono>

#include "controller_manager_test_support.hpp"

namespace servoloop::controller_manager::testing {
namespace {

TEST(ChooseUpdateRate, DivisorsAndNearestAchievableRates) {
  // Exact divisors.
  EXPECT_EQ(chooseUpdateRate(1000.0, 100.0).divisor, 10u);
  EXPECT_TRUE(chooseUpdateRate(1000.0, 100.0).exact);
  EXPECT_DOUBLE_EQ(chooseUpdateRate(1000.0, 100.0).rate_hz, 100.0);
  EXPECT_EQ(chooseUpdateRate(1000.0, 1000.0).divisor, 1u);
  EXPECT_TRUE(chooseUpdateRate(1000.0, 1000.0).exact);
  EXPECT_EQ(chooseUpdateRate(1000.0, 0.5).divisor, 2000u);
  // Not given (<= 0): every cycle.
  EXPECT_EQ(chooseUpdateRate(1000.0, 0.0).divisor, 1u);
  EXPECT_TRUE(chooseUpdateRate(1000.0, 0.0).exact);
  // 1000/300 = 3.33: 1000/3 = 333.3 Hz is 33.3 Hz off, 1000/4 = 250 Hz is 50 Hz off.
  const UpdateRateChoice r300 = chooseUpdateRate(1000.0, 300.0);
  EXPECT_EQ(r300.divisor, 3u);
  EXPECT_NEAR(r300.rate_hz, 1000.0 / 3.0, 1e-9);
  EXPECT_FALSE(r300.exact);
  // 1000/400 = 2.5: 500 Hz is 100 Hz off, 333.3 Hz is 66.7 Hz off.
  EXPECT_EQ(chooseUpdateRate(1000.0, 400.0).divisor, 3u);
  // 1000/450 = 2.22: 500 Hz is 50 Hz off, 333.3 Hz is 116.7 Hz off.
  EXPECT_EQ(chooseUpdateRate(1000.0, 450.0).divisor, 2u);
  // Faster than the manager: every cycle.
  const UpdateRateChoice fast = chooseUpdateRate(1000.0, 2500.0);
  EXPECT_EQ(fast.divisor, 1u);
  EXPECT_FALSE(fast.exact);
  // A manager without a fixed rate runs everything every cycle.
  EXPECT_EQ(chooseUpdateRate(0.0, 50.0).divisor, 1u);
  EXPECT_FALSE(chooseUpdateRate(0.0, 50.0).exact);
  EXPECT_TRUE(chooseUpdateRate(0.0, 0.0).exact);
}

const char* kRateYaml = R"(
fast: {type: test_controllers/EffortController, joint: joint1, record_events: false}
slow: {type: test_controllers/EffortController, joint: joint2, update_rate: 100, record_events: false}
odd: {type: test_controllers/EffortController, joint: joint3, update_rate: 300, record_events: false}
)";

TEST(ControllerManagerRate, HundredHertzInAThousandHertzManagerUpdatesTenTimesLessWithPeriodOneHundredth) {
  ManagerFixture f(kRateYaml, 1000.0);
  ASSERT_TRUE(f.manager.loadController("fast"));
  ASSERT_TRUE(f.manager.loadController("slow"));
  ASSERT_TRUE(f.switchNow({"fast", "slow"}, {}));
  f.cycles_n(1000);

  auto* fast = f.get<EffortTestController>("fast");
  auto* slow = f.get<EffortTestController>("slow");
  EXPECT_EQ(fast->update_calls, 1000);
  EXPECT_EQ(slow->update_calls, 100);
  for (double period : fast->periods) ASSERT_NEAR(period, 0.001, 1e-9);
  // Every slow period, the first one (since starting) included, is 0.01 s.
  ASSERT_EQ(slow->periods.size(), 100u);
  for (double period : slow->periods) ASSERT_NEAR(period, 0.01, 1e-9);
  EXPECT_NEAR(slow->last_update_time.seconds - slow->starting_time.seconds, 1.0, 1e-9);

  const auto specs = f.manager.listControllers();
  EXPECT_DOUBLE_EQ(specs[1].update_rate_hz, 100.0);
  EXPECT_EQ(specs[1].update_divisor, 10u);
}

TEST(ControllerManagerRate, NonDivisorRateUsesTheNearestDivisorWithAWarning) {
  ManagerFixture f(kRateYaml, 1000.0);
  std::string log;
  {
    LogCapture capture;
    ASSERT_TRUE(f.manager.loadController("odd"));
    log = capture.text();
  }
  EXPECT_TRUE(contains(log, "controller 'odd'")) << log;
  EXPECT_TRUE(contains(log, "update_rate 300 Hz")) << log;
  EXPECT_TRUE(contains(log, "1000 Hz")) << log;
  EXPECT_TRUE(contains(log, "333.333 Hz")) << log;

  ASSERT_TRUE(f.switchNow({"odd"}, {}));
  f.cycles_n(999);
  auto* odd = f.get<EffortTestController>("odd");
  EXPECT_EQ(odd->update_calls, 333);
  for (double period : odd->periods) ASSERT_NEAR(period, 0.003, 1e-9);
  EXPECT_EQ(f.manager.listControllers()[0].update_divisor, 3u);
}

TEST(ControllerManagerRate, PeriodIsTheTrueTimeSinceTheLastUpdate) {
  ManagerFixture f(kRateYaml, 1000.0);
  ASSERT_TRUE(f.manager.loadController("slow"));
  ASSERT_TRUE(f.manager.requestSwitch(SwitchRequest{{"slow"}, {}, SwitchStrictness::STRICT, false, 0}));
  // Uneven control times (a loop that overran): the period is the difference
  // of the times the controller actually ran at.
  double t = 0.0;
  std::vector<double> times;
  for (int i = 0; i < 31; ++i) {
    t += (i % 3 == 0) ? 0.0015 : 0.0008;
    times.push_back(t);
    f.manager.update(Time(t), Duration(0.001));
  }
  auto* slow = f.get<EffortTestController>("slow");
  // Started in cycle 0; runs in cycles 10, 20, 30.
  ASSERT_EQ(slow->periods.size(), 3u);
  EXPECT_NEAR(slow->periods[0], times[10] - times[0], 1e-12);
  EXPECT_NEAR(slow->periods[1], times[20] - times[10], 1e-12);
  EXPECT_NEAR(slow->periods[2], times[30] - times[20], 1e-12);
}

TEST(ControllerManagerRate, RestartedControllerCountsFromItsNewStart) {
  ManagerFixture f(kRateYaml, 1000.0);
  ASSERT_TRUE(f.manager.loadController("slow"));
  ASSERT_TRUE(f.switchNow({"slow"}, {}));
  f.cycles_n(15);
  ASSERT_TRUE(f.switchNow({}, {"slow"}));
  f.cycles_n(7);
  ASSERT_TRUE(f.switchNow({"slow"}, {}));
  auto* slow = f.get<EffortTestController>("slow");
  const int before = slow->update_calls;
  f.cycles_n(9);
  EXPECT_EQ(slow->update_calls, before);  // not due until 10 cycles after the restart
  f.cycle();
  EXPECT_EQ(slow->update_calls, before + 1);
  EXPECT_NEAR(slow->periods.back(), 0.01, 1e-9);
}

// Timing each controller's update costs clock reads: a bare manager takes none
// (its updateTimes stay empty); a loop switches timing on for the cycles it
// times, and then every update that ran is counted once.
TEST(ControllerManagerTiming, OffByDefaultAndCountsEveryUpdateOfTheTimedCycles) {
  ManagerFixture f(kRateYaml, 1000.0);
  ASSERT_TRUE(f.manager.loadController("fast"));
  ASSERT_TRUE(f.manager.loadController("slow"));
  ASSERT_TRUE(f.switchNow({"fast", "slow"}, {}));
  f.cycles_n(99);  // 100 cycles since the start
  auto times = f.manager.updateTimes();
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[0].second.count, 0u);
  EXPECT_EQ(times[1].second.count, 0u);

  // 200 timed cycles: the fast controller updates in each, the 100 Hz one in
  // every tenth. The recorded intervals of one cycle do not overlap, so
  // together they fit inside the wall time the cycles took.
  f.manager.setUpdateTiming(true);
  const auto start = std::chrono::steady_clock::now();
  f.cycles_n(200);
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  times = f.manager.updateTimes();
  EXPECT_EQ(times[0].second.count, 200u);
  EXPECT_EQ(times[1].second.count, 20u);
  const double recorded_s = times[0].second.mean_s * 200.0 + times[1].second.mean_s * 20.0;
  EXPECT_GT(times[0].second.min_s, 0.0);
  EXPECT_LE(recorded_s, elapsed_s);

  f.manager.setUpdateTiming(false);
  f.cycles_n(100);
  times = f.manager.updateTimes();
  EXPECT_EQ(times[0].second.count, 200u);
  EXPECT_EQ(times[1].second.count, 20u);
}

}  // namespace
}  // namespace servoloop::controller_manager::testing
