#include "servoloop/node/run_summary.hpp"

#include <fmt/format.h>

namespace servoloop::node {

nlohmann::json toJson(const controller_manager::DurationSnapshot& d) {
  return {{"count", d.count}, {"min", d.min_s}, {"mean", d.mean_s}, {"p50", d.p50_s}, {"p99", d.p99_s}, {"max", d.max_s}};
}

nlohmann::json toJson(const controller_manager::LoopStatisticsSnapshot& loop) {
  return {{"cycles", loop.cycles},
          {"control_updates", loop.control_updates},
          {"sim_time", loop.sim_time_s},
          {"wall_time", loop.wall_time_s},
          {"real_time_factor", loop.real_time_factor},
          {"compute",
           {{"timed_cycles", loop.timed_cycles},
            {"min", loop.compute_min_s},
            {"mean", loop.compute_mean_s},
            {"p50", loop.compute_p50_s},
            {"p99", loop.compute_p99_s},
            {"max", loop.compute_max_s}}},
          {"read", toJson(loop.read)},
          {"write", toJson(loop.write)},
          {"wakeup_latency", toJson(loop.wakeup_latency)},
          {"period_jitter", toJson(loop.period_jitter)},
          {"overruns", loop.overruns},
          {"skipped_deadlines", loop.skipped_deadlines},
          {"schedule_resets", loop.schedule_resets},
          {"hardware_errors", loop.hardware_errors}};
}

RobotSummary summarizeRobot(RobotInstance& robot) {
  RobotSummary summary;
  summary.robot_namespace = robot.robotNamespace();
  summary.backend = robot.backendName();
  const auto times = robot.manager().updateTimes();
  for (const controller_manager::ControllerSpec& controller : robot.manager().listControllers()) {
    controller_manager::DurationSnapshot update_time;
    for (const auto& [name, time] : times) {
      if (name == controller.name) update_time = time;
    }
    summary.controllers.push_back(
        {controller.name, controller.type, toString(controller.state), controller.last_fault, update_time});
  }
  summary.joints = robot.joints();
  summary.loop = robot.loop().statistics().snapshot();
  summary.launch_failures = robot.launchFailures();
  const controller_manager::SafetySupervisor& safety = robot.safety();
  summary.safety_state = controller_manager::toString(safety.state());
  summary.safety_reason = safety.reason();
  summary.protective_stops = safety.protectiveStops();
  summary.emergency_stops = safety.emergencyStops();
  summary.stopped_by_hardware = safety.startsForbidden();
  if (const std::string stuck = robot.stuckReason(); !stuck.empty()) {
    summary.safety_state = "fault";
    summary.safety_reason = stuck;
    summary.stopped_by_hardware = true;
  }
  return summary;
}

nlohmann::json toJson(const RunSummary& summary) {
  nlohmann::json robots = nlohmann::json::array();
  for (const RobotSummary& robot : summary.robots) {
    nlohmann::json controllers = nlohmann::json::array();
    for (const ControllerSummary& controller : robot.controllers) {
      nlohmann::json entry = {{"name", controller.name},
                              {"type", controller.type},
                              {"state", controller.state},
                              {"update_time", toJson(controller.update_time)}};
      if (!controller.last_fault.empty()) entry["last_fault"] = controller.last_fault;
      controllers.push_back(std::move(entry));
    }
    nlohmann::json joints = nlohmann::json::array();
    for (const JointReading& joint : robot.joints) {
      joints.push_back({{"name", joint.name}, {"position", joint.position}, {"velocity", joint.velocity},
                        {"effort", joint.effort}});
    }
    const controller_manager::LoopStatisticsSnapshot& loop = robot.loop;
    robots.push_back({{"namespace", robot.robot_namespace},
                      {"backend", robot.backend},
                      {"controllers", std::move(controllers)},
                      {"joints", std::move(joints)},
                      {"loop", toJson(loop)}});
    robots.back()["safety"] = {{"state", robot.safety_state},
                               {"reason", robot.safety_reason},
                               {"protective_stops", robot.protective_stops},
                               {"emergency_stops", robot.emergency_stops}};
    if (!robot.launch_failures.empty()) robots.back()["launch_failures"] = robot.launch_failures;
  }
  return {{"sim_time", summary.sim_time_s},
          {"wall_time", summary.wall_time_s},
          {"real_time_factor", summary.real_time_factor},
          {"cycles", summary.cycles},
          {"robots", std::move(robots)}};
}

std::string toText(const RunSummary& summary) {
  std::string text = fmt::format("simulated {:.3f} s in {:.3f} s wall (real-time factor {:.3g}), {} cycles\n",
                                 summary.sim_time_s, summary.wall_time_s, summary.real_time_factor, summary.cycles);
  for (const RobotSummary& robot : summary.robots) {
    text += fmt::format("robot {} ({} backend)\n", robot.robot_namespace, robot.backend);
    if (robot.controllers.empty()) text += "  controllers: none loaded\n";
    for (const ControllerSummary& controller : robot.controllers) {
      text += fmt::format("  controller {} ({}): {}{}\n", controller.name, controller.type, controller.state,
                          controller.last_fault.empty() ? "" : " — last fault: " + controller.last_fault);
      if (controller.update_time.count > 0) {
        text += fmt::format("    update() {} (over {} timed updates)\n", controller_manager::toText(controller.update_time),
                            controller.update_time.count);
      }
    }
    for (const JointReading& joint : robot.joints) {
      text += fmt::format("  joint {}: position {:.6g}, velocity {:.6g}, effort {:.6g}\n", joint.name,
                          joint.position, joint.velocity, joint.effort);
    }
    text += "  " + controller_manager::LoopStatistics::summary(robot.loop) + "\n";
    if (robot.loop.read.count > 0) {
      text += fmt::format("  read() {}; write() {}\n", controller_manager::toText(robot.loop.read),
                          controller_manager::toText(robot.loop.write));
    }
    // Said only when the robot was stopped at some point.
    if (robot.safety_state != "running" || robot.protective_stops > 0 || robot.emergency_stops > 0) {
      text += fmt::format("  safety: {} at the end; {} protective stop(s), {} emergency stop(s){}\n", robot.safety_state,
                          robot.protective_stops, robot.emergency_stops,
                          robot.safety_reason.empty() ? "" : " — " + robot.safety_reason);
    }
    for (const std::string& failure : robot.launch_failures) text += "  launch failure: " + failure + "\n";
  }
  return text;
}

}  // namespace servoloop::node
