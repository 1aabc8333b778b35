// What sensors cost per control cycle, as users run them: a node (node::Node,
// as `servoloop launch` builds and runs it, free-running) of the seed arm
// under its position controller, on bullet and on mujoco, with no sensor and
// with 8 sensors of one kind added to its URDF:
//
//   imu           8 IMUs on the moving link, sampled every step
//   imu+noise     the same with Gaussian noise on each of their 9 values
//   force_torque  8 force-torque sensors in its joint
//   contact       8 contact sensors on the moving link (which touches nothing),
//                 sampled and published at 50 Hz (gazebo_ros_bumper's updateRate)
//   imu+ctl       the 8 IMUs with imu_sensor_controller publishing them at 100 Hz
//
// Wall time of 20,000 steps of 1 ms, the kinds alternating with the bare
// arm, median of 7 each; the cost per sensor per cycle is (with - without)
// / (8 × 20,000), and the ratio is with ÷ without, both from this one run.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::bench {
namespace {

namespace fs = std::filesystem;
constexpr std::uint64_t kSteps = 20000;
constexpr int kSensors = 8;
constexpr int kRepetitions = 15;

std::string sensorBlocks(const std::string& kind) {
  std::string out;
  for (int k = 0; k < kSensors; ++k) {
    const std::string name = "s" + std::to_string(k);
    if (kind == "imu" || kind == "imu+ctl" || kind == "imu+noise") {
      const std::string noise = kind == "imu+noise" ? "0.001" : "0";
      out += "<gazebo reference=\"link2\"><sensor name=\"" + name +
             "\" type=\"imu\"><pose>0 0 0.5 0 0 0</pose><plugin name=\"p\" filename=\"libgazebo_ros_imu_sensor.so\">"
             "<gaussianNoise>" + noise + "</gaussianNoise><updateRateHZ>1000</updateRateHZ></plugin></sensor></gazebo>\n";
    } else if (kind == "force_torque") {
      out += "<gazebo reference=\"joint1\"><sensor name=\"" + name + "\" type=\"force_torque\"/></gazebo>\n";
    } else if (kind == "contact") {
      out += "<gazebo reference=\"link2\"><sensor name=\"" + name +
             "\" type=\"contact\"><contact><collision>link2_collision</collision></contact><plugin name=\"b\" "
             "filename=\"libgazebo_ros_bumper.so\"><updateRate>50</updateRate></plugin></sensor></gazebo>\n";
    }
  }
  return out;
}

struct Files {
  fs::path dir;
  Files() : dir(fs::temp_directory_path() / ("servoloop-sensors-bench-" + std::to_string(::getpid()))) {
    fs::create_directories(dir);
    std::ifstream in(sourcePath("robots/one_dof/minimal_robot_description_w_jnt_ctl.urdf"));
    const std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const std::string kind : {"none", "imu", "imu+noise", "force_torque", "contact", "imu+ctl"}) {
      std::string text = urdf;
      text.insert(text.rfind("</robot>"), sensorBlocks(kind));
      std::ofstream(dir / (fileName(kind) + ".urdf")) << text;
    }
    std::ofstream(dir / "controllers.yaml")
        << "one_DOF_robot:\n"
           "  joint1_position_controller:\n    type: effort_controllers/JointPositionController\n"
           "    joint: joint1\n    pid: {p: 10.0, i: 10.0, d: 10.0, i_clamp_min: -10.0, i_clamp_max: 10.0}\n"
           "  imu_sensor_controller: {type: imu_sensor_controller/ImuSensorController, publish_rate: 100}\n";
  }
  ~Files() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  static std::string fileName(std::string kind) {
    std::replace(kind.begin(), kind.end(), '+', '_');
    return kind;
  }
};

double runNode(const Files& files, const std::string& backend, const std::string& kind) {
  std::string controllers = "[joint1_position_controller";
  if (kind == "imu+ctl") controllers += ", imu_sensor_controller";
  controllers += "]";
  const std::string yaml = "world: {backend: " + backend +
                           ", time_step: 0.001, ground_plane: false}\n"
                           "controller_manager: {update_rate: 1000}\n"
                           "robots:\n  - {urdf: " + Files::fileName(kind) +
                           ".urdf, params: [controllers.yaml], controllers: " + controllers +
                           "}\n"
                           "publish:\n  - {topic: /one_DOF_robot/joint1_position_controller/command, "
                           "type: std_msgs/Float64, time: 0.0, value: 1.0}\n";
  return wallSecondsOfNodeRun(yaml, files.dir, static_cast<double>(kSteps) * 0.001);
}

}  // namespace
}  // namespace servoloop::bench

int main(int argc, char** argv) {
  using namespace servoloop::bench;
  servoloop::setLogLevel("warn");
  std::vector<std::string> backends{"bullet"};
  for (int i = 1; i < argc; ++i) backends.push_back(argv[i]);  // e.g. mujoco
  const Files files;
  std::printf("=== Sensors: the seed arm, %llu steps of 1 ms, %d sensors of a kind; wall time, median of %d alternating pairs (the cost: of the pairs' differences) ===\n",
              static_cast<unsigned long long>(kSteps), kSensors, kRepetitions);
  std::printf("%-8s %-14s %12s %12s %10s %22s\n", "engine", "sensors", "none (ms)", "with (ms)", "ratio",
              "per sensor per cycle");
  for (const std::string& backend : backends) {
    for (const std::string kind : {"imu", "imu+noise", "force_torque", "contact", "imu+ctl"}) {
      // Pairs in alternating order; the cost is the median of the pairs'
      // differences, which a slow stretch of the machine shifts less than the
      // difference of two medians.
      std::vector<double> bare, with, differences;
      for (int r = 0; r < kRepetitions; ++r) {
        const bool bare_first = r % 2 == 0;
        const double first = runNode(files, backend, bare_first ? "none" : kind);
        const double second = runNode(files, backend, bare_first ? kind : "none");
        bare.push_back(bare_first ? first : second);
        with.push_back(bare_first ? second : first);
        differences.push_back(with.back() - bare.back());
      }
      const double bare_s = median(bare), with_s = median(with);
      const double per_sensor_ns = median(differences) / (kSensors * static_cast<double>(kSteps)) * 1e9;
      std::printf("%-8s %-14s %12.1f %12.1f %10.3f %19.0f ns\n", backend.c_str(), kind.c_str(), bare_s * 1e3,
                  with_s * 1e3, with_s / bare_s, per_sensor_ns);
    }
  }
  return 0;
}
