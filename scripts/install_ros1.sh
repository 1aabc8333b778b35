#!/usr/bin/env bash
# Installs Debian 12's ROS 1 packages the optional ROS 1 bridge builds and is
# tested with (docs/ros1.md): roscore and the command-line tools (rostopic,
# rosservice, rosparam, rosbag), roscpp and the message headers, the message
# generators, the Python message packages the tools read, and
# robot_state_publisher, dynamic_reconfigure (its message headers for the
# bridge, dynparam for the tests) and rosrun. The next build finds them and builds the bridge.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh \
  ros-core libroscpp-dev \
  libstd-msgs-dev libsensor-msgs-dev libgeometry-msgs-dev libnav-msgs-dev libtrajectory-msgs-dev \
  libtf2-msgs-dev libros-rosgraph-msgs-dev libdiagnostic-msgs-dev libstd-srvs-dev python3-std-srvs \
  ros-std-msgs ros-geometry-msgs ros-trajectory-msgs python3-gencpp python3-genpy \
  python3-std-msgs python3-sensor-msgs python3-geometry-msgs python3-nav-msgs python3-trajectory-msgs \
  python3-tf2-msgs python3-diagnostic-msgs python3-rosgraph-msgs \
  libactionlib-dev libactionlib-msgs-dev ros-actionlib-msgs python3-actionlib-msgs \
  ros-robot-state-publisher libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure rosbash
