// The seed's first setup, robots/one_dof/one_dof_raw_pd.launch.yaml: the
// one-DOF robot without a <transmission> (minimal_robot_description.urdf,
// joint1 continuous) under minimal_joint_controller/MinimalJointController
// (kp 10, kv 3, 100 Hz), commanded to 1.0 rad from rest at q = 0 (the launch
// file's `--pub .../pos_cmd:=1.0`, published at t = 0). The whole trajectory
// q(t), q̇(t), sampled every physics step for 5 s, is compared with an
// independent reference: the rigid-body equation written by hand from the URDF
// and integrated with RK4 at 10 µs, closed through the same discrete
// controller (effort sampled from the state every 10 ms and held in between).
//
// The run goes the way `servoloop launch` runs the file: the launch file read
// by the node's loader, the backend (BulletRobotHW, and MujocoRobotHW when
// MuJoCo is built) initialised with the world settings, the controllers from
// the launch file loaded from their YAML by a ControllerManager at the launch
// file's update rate, started before t = 0 as the node starts them, and
// stepped by a SimulationLoop.
//
// Equation of motion, from minimal_robot_description.urdf:
//   joint1: continuous, origin xyz="0 0 1" in link1 (link1 is fixed to the
//     world: the axis sits 1 m above the world origin), axis xyz="0 1 0";
//     no <dynamics> (no damping, no friction), no <limit>.
//   link2 <inertial>: origin xyz="0 0 0.5", mass 1, iyy 0.1 (about the centre
//     of mass, axis y).
//   gravity (launch file): (0, 0, −9.81) m/s².
//   Rotating link2 by q about +y takes its centre of mass from (0, 0, 0.5) to
//   (0.5 sin q, 0, 0.5 cos q) relative to the axis, so its height is
//   1 + 0.5 cos q and V(q) = m g (1 + d cos q) with m = 1, d = 0.5. The
//   gravity torque about the axis is −dV/dq = m g d sin q (q = 0 is upright,
//   an unstable equilibrium). Inertia about the axis (parallel axes):
//   I = iyy + m d² = 0.1 + 1·0.25 = 0.35 kg·m². So
//     I q̈ = τ + m g d sin q,   I = 0.35 kg·m²,  m g d = 4.905 N·m,
//   with τ = kp·wrap(q_cmd − q_k) − kv·q̇_k held over [t_k, t_k + 10 ms), where
//   (q_k, q̇_k) is the state at the controller update t_k = k·10 ms.
//   (Steady state: 10 (1 − q) + 4.905 sin q = 0 → q ≈ 1.4889 rad.)
//
// Tolerances, from the physics step dt (1 ms in the launch file):
//  - bullet integrates with semi-implicit Euler, first order in dt: each step
//    v += a·dt, then q += v·dt. Against the exact motion its position gains
//    dt²·a/2 per step (it moves dt·v_{k+1} where the exact motion moves about
//    dt·(v_k + v_{k+1})/2), so the lead after a stretch of steps is
//    dt/2·|Δq̇| over that stretch: at most dt·max|q̇| over the run (the damped
//    response here rises to one velocity peak and falls back). Its velocity
//    takes a(t_k) for the whole step where the exact motion averages a over
//    the step, so it gains dt²/2·ȧ per step, dt/2·|Δq̈| over a stretch in
//    which the effort is held; the effort only changes at controller updates,
//    where both see the same jump, so the velocity error stays within
//    dt·max|q̈| over the run. The bounds are:
//      position  dt·max|q̇_reference|   (1 ms · 2.58 rad/s ≈ 2.6e-3 rad; measured 1.1e-3)
//      velocity  dt·max|q̈_reference|   (≈ 1 ms · 28.6 rad/s² ≈ 2.9e-2 rad/s)
//    and BulletErrorIsFirstOrderInTheStep checks that halving dt halves the
//    error, i.e. that the distance to the reference is integration error.
//    (The velocity bound is loose, the measured error is about 3e-3 rad/s: the
//    position lead of semi-implicit Euler largely makes up for the late
//    acceleration; the halving check is the sharp one.)
//  - mujoco integrates with RK4 (O(dt⁴)) and the effort is constant within
//    each of its steps: with the loop's ω ≈ 6 rad/s, (ω·dt)⁴ ≈ 1.3e-9 per unit
//    time on a motion of ~1.5 rad over 5 s → ~1e-8 rad; bounds ten times
//    that, 1e-7 rad, and ω·1e-7 → 1e-6 rad/s (measured: ~1e-12).
// A modelling error shows as far more: the test checks that a reference with
// kv = 0, with link2's mass doubled or with the second URDF's damping 1
// N·m·s/rad is at least 10 times the bullet bound away from the bullet run.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "bullet_robot_hw.hpp"
#include "rk4_reference.hpp"
#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/controllers/joint_state_controller/joint_state_controller.hpp"
#include "servoloop/controllers/minimal_joint_controller/minimal_joint_controller.hpp"
#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/description/robot_model.hpp"
#include "sim_test_support.hpp"
#ifdef SERVOLOOP_HAVE_MUJOCO
#include "mujoco_robot_hw.hpp"
#endif

namespace servoloop {
namespace {

namespace cm = controller_manager;
namespace hi = hardware_interface;

const std::filesystem::path kLaunchFile =
    std::filesystem::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof" / "one_dof_raw_pd.launch.yaml";
const std::string kCommandTopic = "/one_DOF_robot/minimal_joint_controller/pos_cmd";
constexpr double kCommand = 1.0;   // rad, the launch file's --pub example
constexpr double kDuration = 5.0;  // s: the response has settled to ~1e-3 rad of its steady state
constexpr double kMujocoPositionTolerance = 1e-7;  // rad, see above
constexpr double kMujocoVelocityTolerance = 1e-6;  // rad/s, see above

// I q̈ = τ + gravity_torque·sin q − damping·q̇ (see the derivation above).
struct Plant {
  double inertia;         // kg·m² about joint1's axis
  double gravity_torque;  // m g d, N·m
  double damping;         // N·m·s/rad
};
constexpr double kLink2Mass = 1.0, kLink2ComDistance = 0.5, kLink2Iyy = 0.1, kGravity = 9.81;
constexpr Plant kUrdfPlant{kLink2Iyy + kLink2Mass * kLink2ComDistance * kLink2ComDistance,
                           kLink2Mass * kGravity * kLink2ComDistance, 0.0};

struct Gains {
  double kp;       // N·m/rad
  double kv;       // N·m·s/rad
  double rate_hz;  // controller updates per second
};

// Sample n at t = n·dt; effort[n] acts over [t_n, t_n + dt).
struct Trajectory {
  double dt = 0.0;
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> effort;
};

struct ScenarioRun {
  Trajectory trajectory;
  Gains gains{};
  std::uint64_t control_updates = 0;
  std::vector<double> reported_effort;  // the joint's effort as the hardware read it (applied over the step before)
};

void require(bool condition, const std::string& what) {
  if (!condition) throw std::runtime_error(what);
}

// The command error as the controller wraps it, into (−π, π].
double wrapToPi(double angle) {
  const double wrapped = std::remainder(angle, 2.0 * M_PI);
  return wrapped == -M_PI ? M_PI : wrapped;
}

// As `servoloop launch` starts the launch file's controllers: the hardware is
// read at t = 0, then each controller is started d manager periods before
// t = 0 (d: its rate divisor, 10 for the 100 Hz raw PD in the 1 kHz manager)
// in manager updates that step no physics, so that every controller updates
// first at t = 0 and then every d-th cycle.
void startBeforeTimeZero(hi::SimulatedRobotHW& hw, cm::ControllerManager& manager, const cm::SimulationLoop& loop,
                         const std::vector<std::string>& controllers) {
  std::map<std::uint32_t, std::vector<std::string>, std::greater<>> by_divisor;
  for (const cm::ControllerSpec& spec : manager.listControllers()) {
    if (std::find(controllers.begin(), controllers.end(), spec.name) != controllers.end()) {
      by_divisor[std::max<std::uint32_t>(spec.update_divisor, 1)].push_back(spec.name);
    }
  }
  require(!by_divisor.empty(), "no controller to start");
  const Duration period = loop.controlPeriod();
  require(hw.read(Time(0.0), loop.physicsStep()) == ReturnType::ok, "reading the hardware failed");
  for (std::uint32_t cycles_before = by_divisor.begin()->first; cycles_before >= 1; --cycles_before) {
    if (const auto group = by_divisor.find(cycles_before); group != by_divisor.end()) {
      cm::SwitchRequest request;
      request.start_controllers = group->second;
      const cm::ServiceResult result = manager.requestSwitch(request);
      require(static_cast<bool>(result), "starting controllers failed: " + result.message);
    }
    manager.update(Time(-static_cast<double>(cycles_before) * period.seconds), period);
  }
  require(!manager.switchPending(), "the controller switch did not happen");
}

// Runs the launch file's scenario on `Backend` for kDuration at the physics
// step time_step_s (the launch file's, unless given).
template <class Backend>
ScenarioRun runScenario(double time_step_s = 0.0) {
  const servoloop::node::LaunchFile launch = servoloop::node::loadLaunchFile(kLaunchFile);
  require(launch.robots.size() == 1 && launch.robots[0].params.size() == 1, "one robot with one parameter file");
  const servoloop::node::RobotSpec& robot = launch.robots[0];
  require(robot.urdf.filename() == "minimal_robot_description.urdf", "the first seed URDF");
  require(robot.robot_namespace == "/one_DOF_robot", "namespace /one_DOF_robot");
  const double dt = time_step_s > 0.0 ? time_step_s : launch.world.time_step_s;

  // The robot namespace's parameters, with the world settings where the node
  // writes them (<ns>/sim).
  YAML::Node params = YAML::LoadFile(robot.params[0].file.string())["one_DOF_robot"];
  require(params["minimal_joint_controller"]["type"].as<std::string>() ==
              "minimal_joint_controller/MinimalJointController",
          "the raw PD controller");
  params["sim"]["time_step"] = dt;
  params["sim"]["gravity"] = std::vector<double>(launch.world.gravity.begin(), launch.world.gravity.end());
  params["sim"]["ground_plane"] = launch.world.ground_plane;

  hi::HardwareInfo info;
  info.urdf_path = robot.urdf.string();
  info.urdf_xml = sim_testing::readFile(info.urdf_path);
  info.robot_namespace = robot.robot_namespace;
  info.parameters = params;
  Backend hw;
  hw.init(info);

  servoloop::realtime::TopicBus bus;
  auto factory = std::make_shared<cm::InProcessControllerFactory>();
  factory->add<controllers::MinimalJointController>("minimal_joint_controller/MinimalJointController");
  factory->add<controllers::JointStateController>("joint_state_controller/JointStateController");
  cm::ControllerContext context;
  context.robot_namespace = robot.robot_namespace;
  context.topics = &bus;
  context.robot_model = parseRobotModel(info.urdf_xml, info.urdf_path);
  cm::ControllerManager manager(&hw, factory, cm::ControllerManager::lookupIn(params), context,
                                launch.controller_manager.update_rate_hz);
  cm::SimulationLoop::Options options;
  options.topic_bus = &bus;
  cm::SimulationLoop loop(hw, manager, options);

  for (const std::string& name : robot.controllers) {
    const cm::ServiceResult result = manager.loadController(name);
    require(static_cast<bool>(result), "loading " + name + " failed: " + result.message);
  }
  startBeforeTimeZero(hw, manager, loop, robot.controllers);
  // After the start: a controller's starting() forgets earlier commands.
  bus.publish(kCommandTopic, servoloop::std_msgs::Float64{kCommand});

  const auto* pd = dynamic_cast<const controllers::MinimalJointController*>(
      manager.getController("minimal_joint_controller"));
  require(pd != nullptr, "minimal_joint_controller is a MinimalJointController");
  const hi::JointStateHandle joint = hw.template get<hi::JointStateInterface>()->getHandle("joint1");

  ScenarioRun run;
  run.gains = {pd->kp(), pd->kv(), pd->updateRate()};
  run.trajectory.dt = dt;
  const int steps = static_cast<int>(std::lround(kDuration / dt));
  for (int n = 0; n < steps; ++n) {
    // One cycle: read (the state at t_n), control update when due, write, step.
    require(loop.cycleOnce() == ReturnType::ok, "a loop cycle failed");
    run.trajectory.position.push_back(joint.getPosition());
    run.trajectory.velocity.push_back(joint.getVelocity());
    run.reported_effort.push_back(joint.getEffort());
    run.trajectory.effort.push_back(pd->effortCommand());
    bus.flush();
  }
  run.control_updates = pd->controlUpdates();
  return run;
}

// The reference: the plant integrated with RK4 at 10 µs, sampled every dt,
// under the raw PD computed from the sampled state every control period and
// held in between.
Trajectory reference(const Plant& plant, const Gains& gains, double dt, double h_s = 1e-5) {
  const int steps_per_update = static_cast<int>(std::lround(1.0 / (gains.rate_hz * dt)));
  const int steps = static_cast<int>(std::lround(kDuration / dt));
  Trajectory out;
  out.dt = dt;
  double q = 0.0, v = 0.0;  // at rest, upright
  while (static_cast<int>(out.position.size()) < steps) {
    const double effort = gains.kp * wrapToPi(kCommand - q) - gains.kv * v;
    const auto period = sim_testing::integrateRk4(
        [&](double qq, double vv) {
          return (effort + plant.gravity_torque * std::sin(qq) - plant.damping * vv) / plant.inertia;
        },
        q, v, steps_per_update * dt, dt, h_s);
    for (int i = 0; i < steps_per_update && static_cast<int>(out.position.size()) < steps; ++i) {
      out.position.push_back(period[i].position[0]);
      out.velocity.push_back(period[i].velocity[0]);
      out.effort.push_back(effort);
    }
    q = period.back().position[0];
    v = period.back().velocity[0];
  }
  return out;
}

double maxAbs(const std::vector<double>& values) {
  double largest = 0.0;
  for (const double value : values) largest = std::max(largest, std::abs(value));
  return largest;
}

// Largest |q̈| of a trajectory, from the plant at its samples (the first
// sample after each effort change included).
double maxAcceleration(const Trajectory& t, const Plant& plant) {
  double largest = 0.0;
  for (std::size_t n = 0; n < t.position.size(); ++n) {
    const double a =
        (t.effort[n] + plant.gravity_torque * std::sin(t.position[n]) - plant.damping * t.velocity[n]) / plant.inertia;
    largest = std::max(largest, std::abs(a));
  }
  return largest;
}

struct Deviation {
  double position = 0.0;  // rad, largest over the samples
  double velocity = 0.0;  // rad/s
  std::size_t worst_position_sample = 0;
  std::size_t worst_velocity_sample = 0;
};

Deviation deviation(const Trajectory& a, const Trajectory& b) {
  Deviation d;
  const std::size_t samples = std::min(a.position.size(), b.position.size());
  for (std::size_t n = 0; n < samples; ++n) {
    if (const double e = std::abs(a.position[n] - b.position[n]); e > d.position) {
      d.position = e;
      d.worst_position_sample = n;
    }
    if (const double e = std::abs(a.velocity[n] - b.velocity[n]); e > d.velocity) {
      d.velocity = e;
      d.worst_velocity_sample = n;
    }
  }
  return d;
}

// The run is the scenario the reference assumes: the YAML's gains, every
// physics step sampled, one control update every 10 ms with the effort
// computed from the state the hardware read at that step and held until the
// next, and that effort applied unchanged (no limit cuts it).
void expectTheScenarioTheReferenceAssumes(const ScenarioRun& run) {
  const Trajectory& t = run.trajectory;
  ASSERT_EQ(t.position.size(), static_cast<std::size_t>(std::lround(kDuration / t.dt)));
  const YAML::Node yaml = YAML::LoadFile(
      (std::filesystem::path(SERVOLOOP_SOURCE_DIR) / "robots/one_dof/control_config/minimal_joint_controller.yaml")
          .string())["one_DOF_robot"]["minimal_joint_controller"];
  EXPECT_EQ(run.gains.kp, yaml["kp"].as<double>());
  EXPECT_EQ(run.gains.kv, yaml["kv"].as<double>());
  EXPECT_EQ(run.gains.rate_hz, yaml["update_rate"].as<double>());
  const auto steps_per_update = static_cast<std::size_t>(std::lround(1.0 / (run.gains.rate_hz * t.dt)));
  EXPECT_EQ(run.control_updates, t.position.size() / steps_per_update);
  EXPECT_EQ(t.position[0], 0.0);
  EXPECT_EQ(t.velocity[0], 0.0);
  EXPECT_EQ(t.effort[0], run.gains.kp * kCommand) << "the first update at t = 0 sees the command";
  for (std::size_t n = 0; n < t.position.size(); ++n) {
    if (n % steps_per_update == 0) {
      const double expected = run.gains.kp * wrapToPi(kCommand - t.position[n]) - run.gains.kv * t.velocity[n];
      ASSERT_NEAR(t.effort[n], expected, 1e-12) << "control update at t = " << n * t.dt << " s";
    } else {
      ASSERT_EQ(t.effort[n], t.effort[n - 1]) << "the effort is held between updates (t = " << n * t.dt << " s)";
    }
    if (n > 0) {
      ASSERT_NEAR(run.reported_effort[n], t.effort[n - 1], 1e-9)
          << "the joint's effort over the step before t = " << n * t.dt << " s is the controller's";
    }
  }
}

void report(const char* what, const Deviation& d, double dt, double position_bound, double velocity_bound) {
  std::printf("%s: |q - q_ref| %.3g rad at t = %.3f s (bound %.3g), |q̇ - q̇_ref| %.3g rad/s at t = %.3f s "
              "(bound %.3g)\n",
              what, d.position, d.worst_position_sample * dt, position_bound, d.velocity,
              d.worst_velocity_sample * dt, velocity_bound);
}

TEST(RawPdTrajectory, ReferenceSettlesAtTheGravityBalance) {
  // The reference itself: the response settles where 10 (1 − q) = −4.905 sin q.
  const Trajectory ref = reference(kUrdfPlant, {10.0, 3.0, 100.0}, 0.001);
  double q = 1.5;  // Newton on kp (cmd − q) + m g d sin q = 0
  for (int i = 0; i < 50; ++i) {
    q -= (10.0 * (kCommand - q) + kUrdfPlant.gravity_torque * std::sin(q)) /
         (-10.0 + kUrdfPlant.gravity_torque * std::cos(q));
  }
  EXPECT_NEAR(q, 1.4889, 1e-4);
  std::printf("reference: q(5 s) = %.6f rad, peak %.6f rad, balance %.6f rad\n", ref.position.back(),
              maxAbs(ref.position), q);
  EXPECT_NEAR(ref.position.back(), q, 1e-4);
  // ζ ≈ 3 / (2·√(9.6·0.35)) ≈ 0.8 about the balance: a small overshoot first.
  EXPECT_GT(maxAbs(ref.position), q + 1e-3) << "the response overshoots the balance before settling";
}

TEST(RawPdTrajectory, BulletFollowsTheReferenceAtEveryStep) {
  const ScenarioRun run = runScenario<sim_bullet::BulletRobotHW>();
  expectTheScenarioTheReferenceAssumes(run);
  const Trajectory& bullet = run.trajectory;
  const Trajectory ref = reference(kUrdfPlant, run.gains, bullet.dt);
  const double position_bound = bullet.dt * maxAbs(ref.velocity);
  const double velocity_bound = bullet.dt * maxAcceleration(ref, kUrdfPlant);
  const Deviation d = deviation(bullet, ref);
  report("bullet vs reference", d, bullet.dt, position_bound, velocity_bound);
  EXPECT_LT(d.position, position_bound) << "worst at t = " << d.worst_position_sample * bullet.dt << " s";
  EXPECT_LT(d.velocity, velocity_bound) << "worst at t = " << d.worst_velocity_sample * bullet.dt << " s";

  // Wrong physics or a wrong controller is far outside the bound.
  struct WrongModel {
    const char* what;
    Plant plant;
    Gains gains;
  };
  const Plant doubled_mass{kLink2Iyy + 2.0 * kLink2Mass * kLink2ComDistance * kLink2ComDistance,
                           2.0 * kLink2Mass * kGravity * kLink2ComDistance, 0.0};
  const Plant damped{kUrdfPlant.inertia, kUrdfPlant.gravity_torque, 1.0};
  const std::vector<WrongModel> wrong = {
      {"kv = 0", kUrdfPlant, {run.gains.kp, 0.0, run.gains.rate_hz}},
      {"link2 mass doubled", doubled_mass, run.gains},
      {"damping 1 N·m·s/rad", damped, run.gains},
  };
  for (const WrongModel& model : wrong) {
    const Deviation off = deviation(bullet, reference(model.plant, model.gains, bullet.dt));
    std::printf("bullet vs a reference with %s: %.3g rad (%.0f x the bound)\n", model.what, off.position,
                off.position / position_bound);
    EXPECT_GT(off.position, 10.0 * position_bound) << model.what << ": the comparison must see this error";
  }
}

TEST(RawPdTrajectory, BulletErrorIsFirstOrderInTheStep) {
  // Halving the physics step (the controller still updates every 10 ms, now
  // every 20th step) halves bullet's distance from the reference: the
  // remaining difference is semi-implicit Euler's first-order error.
  const auto errors = [](double dt) {
    const ScenarioRun run = runScenario<sim_bullet::BulletRobotHW>(dt);
    expectTheScenarioTheReferenceAssumes(run);
    return deviation(run.trajectory, reference(kUrdfPlant, run.gains, dt));
  };
  const Deviation coarse = errors(0.001);
  const Deviation fine = errors(0.0005);
  std::printf("bullet vs reference: position %.3g rad at dt = 1 ms, %.3g rad at 0.5 ms (ratio %.2f); "
              "velocity %.3g rad/s, %.3g rad/s (ratio %.2f)\n",
              coarse.position, fine.position, coarse.position / fine.position, coarse.velocity, fine.velocity,
              coarse.velocity / fine.velocity);
  EXPECT_NEAR(coarse.position / fine.position, 2.0, 0.3);
  EXPECT_NEAR(coarse.velocity / fine.velocity, 2.0, 0.3);
}

#ifdef SERVOLOOP_HAVE_MUJOCO
TEST(RawPdTrajectory, MujocoFollowsTheReferenceAtEveryStep) {
  const ScenarioRun run = runScenario<sim_mujoco::MujocoRobotHW>();
  expectTheScenarioTheReferenceAssumes(run);
  const Trajectory& mujoco = run.trajectory;
  const Trajectory ref = reference(kUrdfPlant, run.gains, mujoco.dt);
  const Deviation d = deviation(mujoco, ref);
  report("mujoco vs reference", d, mujoco.dt, kMujocoPositionTolerance, kMujocoVelocityTolerance);
  EXPECT_LT(d.position, kMujocoPositionTolerance) << "worst at t = " << d.worst_position_sample * mujoco.dt << " s";
  EXPECT_LT(d.velocity, kMujocoVelocityTolerance) << "worst at t = " << d.worst_velocity_sample * mujoco.dt << " s";
}
#endif

}  // namespace
}  // namespace servoloop
