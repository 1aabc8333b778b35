#pragma once
// ros_control's dynamic_reconfigure of a controller's PID gains, for every
// PID of every loaded controller (control.gains): under
// <ns>/<controller>/<pid> ("pid", "<joint>/pid", "gains/<joint>", where
// control_toolbox's Pid serves it) the service set_parameters
// (dynamic_reconfigure/Reconfigure) and the latched topics
// parameter_descriptions and parameter_updates, with control_toolbox's
// parameters p, i, d, i_clamp_min, i_clamp_max and antiwindup and their ranges.
// `dynparam set|get|list` and rqt_reconfigure change a running controller's
// gains; the node takes them at the controller's next update.
//
// As a dynamic_reconfigure server does, a value outside its range is clamped
// to it, the parameters are written to the parameter server, and the reply and
// parameter_updates carry the gains as they are now (unchanged, with an error
// logged, when the node refuses them).
#include <map>
#include <memory>
#include <string>

#include <ros/node_handle.h>

#include "node_link.hpp"

namespace servoloop::ros1 {

class PidReconfigureServers {
 public:
  // `link`: a connection of the servers' own (service calls and discovery).
  PidReconfigureServers(ros::NodeHandle& nh, NodeLink& link);
  ~PidReconfigureServers();
  PidReconfigureServers(const PidReconfigureServers&) = delete;
  PidReconfigureServers& operator=(const PidReconfigureServers&) = delete;

  // Serves the PIDs of controllers loaded since the last call and drops those
  // of controllers unloaded (control.list, control.gains). From one thread.
  void discover();

 private:
  struct Server;
  ros::NodeHandle& nh_;
  NodeLink& link_;
  std::map<std::string, std::unique_ptr<Server>> servers_;  // by "<controller>/<pid>"; only discover() touches it
};

}  // namespace servoloop::ros1
