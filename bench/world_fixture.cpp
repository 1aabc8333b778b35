#include "world_fixture.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include "bench_support.hpp"
#include "loop_fixtures.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_scene.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::bench {

namespace fs = std::filesystem;

const char* const kBoxUrdf = R"(<robot name="box"><link name="box">
<inertial><mass value="1"/><inertia ixx="0.0067" ixy="0" ixz="0" iyy="0.0067" iyz="0" izz="0.0067"/></inertial>
<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>)";

double boxX(int k) { return 0.5 * (k % 4); }
double boxY(int k) { return -2.0 - 0.5 * (k / 4); }
double armX(int k) { return 1.5 * k; }

WorldFiles::WorldFiles(int arms, const fs::path& folder)
    : dir(folder.empty() ? fs::temp_directory_path() / ("servoloop-world-bench-" + std::to_string(::getpid()))
                         : folder),
      keep(!folder.empty()) {
  fs::create_directories(dir);
  std::ifstream in(sourcePath("robots/one_dof/minimal_robot_description_w_jnt_ctl.urdf"));
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t gazebo = urdf.find("<gazebo>");
  urdf.erase(gazebo, urdf.find("</gazebo>", gazebo) + 9 - gazebo);
  std::ofstream(dir / "arm.urdf") << urdf;
  std::ofstream(dir / "box.urdf") << kBoxUrdf;
  std::ofstream params(dir / "arms.yaml");
  for (int k = 0; k < arms; ++k) {
    params << "arm" << k
           << ":\n  joint_state_controller: {type: joint_state_controller/JointStateController, publish_rate: 50}\n"
              "  joint1_position_controller:\n    type: effort_controllers/JointPositionController\n"
              "    joint: joint1\n    pid: {p: 10.0, i: 10.0, d: 10.0, i_clamp_min: -10.0, i_clamp_max: 10.0}\n";
  }
}

WorldFiles::~WorldFiles() {
  std::error_code ec;
  if (!keep) fs::remove_all(dir, ec);
}

std::string worldLaunchText(const std::string& backend, int arms, bool shared) {
  std::string yaml = "world: {backend: " + backend + ", time_step: 0.001, ground_plane: true, shared: " +
                     std::string(shared ? "true" : "false") + "}\ncontroller_manager: {update_rate: 1000}\nrobots:\n";
  for (int k = 0; k < arms; ++k) {
    yaml += "  - {urdf: arm.urdf, model: arm" + std::to_string(k) + ", namespace: /arm" + std::to_string(k) +
            ", params: [arms.yaml], pose: [" + std::to_string(armX(k)) +
            ", 0, 0, 0, 0, 0], controllers: [joint_state_controller, joint1_position_controller]}\n";
  }
  for (int k = 0; k < kWorldBoxes; ++k) {
    yaml += "  - {urdf: box.urdf, model: box" + std::to_string(k) + ", namespace: /box" + std::to_string(k) +
            ", pose: [" + std::to_string(boxX(k)) + ", " + std::to_string(boxY(k)) + ", 0.1, 0, 0, 0]}\n";
  }
  yaml += "publish:\n";
  for (int k = 0; k < arms; ++k) {
    yaml += "  - {topic: /arm" + std::to_string(k) +
            "/joint1_position_controller/command, type: std_msgs/Float64, time: 0.0, value: 1.0}\n";
  }
  return yaml;
}

struct RawBulletWorld::State {
  struct Arm {
    sim_bullet::BulletWorld* world;
    std::size_t joint;
    HandWrittenPositionLaw law;
  };
  std::unique_ptr<sim_bullet::BulletScene> scene;
  std::vector<std::unique_ptr<sim_bullet::BulletWorld>> bodies;
  std::vector<Arm> arms;
};

RawBulletWorld::RawBulletWorld(const WorldFiles& files, int arms) : state_(std::make_unique<State>()) {
  const auto arm_model = loadRobotModelFile((files.dir / "arm.urdf").string());
  const auto box_model = parseRobotModel(kBoxUrdf, "box");
  sim_bullet::SceneSettings scene_settings;
  scene_settings.time_step_s = kTimeStepS;
  scene_settings.ground_plane = true;
  state_->scene = std::make_unique<sim_bullet::BulletScene>(scene_settings);
  const RobotCase seed = seedRobot();
  const YAML::Node params = seed.namespaceParams();
  for (int k = 0; k < arms; ++k) {
    sim_bullet::WorldSettings settings;
    settings.time_step_s = kTimeStepS;
    settings.ground_plane = true;
    settings.fixed_base = sim_bullet::FixedBase::fixed;
    settings.initial_base_position = Eigen::Vector3d(armX(k), 0.0, 0.0);
    auto& body = state_->bodies.emplace_back(std::make_unique<sim_bullet::BulletWorld>(*arm_model, settings, *state_->scene));
    HandWrittenPositionLaw law = HandWrittenPositionLaw::forJoint(seed, params, 0, *arm_model);
    law.setpoint_rad = 1.0;
    state_->arms.push_back({body.get(), body->jointIndex("joint1"), law});
  }
  for (int k = 0; k < kWorldBoxes; ++k) {
    sim_bullet::WorldSettings settings;
    settings.time_step_s = kTimeStepS;
    settings.ground_plane = true;
    settings.fixed_base = sim_bullet::FixedBase::floating;
    settings.initial_base_position = Eigen::Vector3d(boxX(k), boxY(k), 0.1);
    state_->bodies.push_back(std::make_unique<sim_bullet::BulletWorld>(*box_model, settings, *state_->scene));
  }
  state_->scene->restart();
}

RawBulletWorld::~RawBulletWorld() {
  state_->bodies.clear();  // before the scene
}

void RawBulletWorld::step(std::uint64_t steps) {
  for (std::uint64_t n = 0; n < steps; ++n) {
    for (State::Arm& arm : state_->arms) {
      arm.world->setJointEffort(
          arm.joint, arm.law.effort(arm.world->jointPosition(arm.joint), arm.world->jointVelocity(arm.joint)));
    }
    state_->scene->step();
  }
}

double RawBulletWorld::firstArmPosition() const {
  const State::Arm& arm = state_->arms.front();
  return arm.world->jointPosition(arm.joint);
}

RunTimes runRawBulletWorld(const WorldFiles& files, int arms, std::uint64_t steps) {
  RawBulletWorld world(files, arms);
  const RunTimer timer;
  world.step(steps);
  const RunTimes times = timer.elapsed();
  // The seed's gains take about 20 s to settle; in 5 s the arm is well on its way.
  if (!(world.firstArmPosition() > 0.5)) {
    std::fprintf(stderr, "raw bullet: the first arm did not swing towards its setpoint\n");
  }
  return times;
}

}  // namespace servoloop::bench
