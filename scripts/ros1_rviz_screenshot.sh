#!/usr/bin/env bash
# rviz showing the seed robot driven by servoloop through the ROS 1 bridge,
# captured to a PNG (docs/ros1.md). Runs roscore, the node (joint1 commanded
# to 1 rad), the bridge, robot_state_publisher and rviz under Xvfb.
#   OUT        the PNG (default: docs/ros1/seed_in_rviz.png)
#   BUILD_DIR  build folder (default: build)
# Needs: bash scripts/install_ros1.sh; apt install rviz xvfb imagemagick
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
bin="$build/bin"
out=${OUT:-docs/ros1/seed_in_rviz.png}
# shellcheck source=scripts/ros1_session.sh
source scripts/ros1_session.sh
display=:$(( 90 + RANDOM % 9 ))
start_roscore
start_background node.log "$bin/servoloop" launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml --rtf 1 --ros1-bridge \
  --pub /one_DOF_robot/joint1_position_controller/command:=1.0
until rostopic list 2>/dev/null | grep -q /one_DOF_robot/joint_states; do sleep 0.2; done
start_background rsp.log /usr/lib/robot_state_publisher/robot_state_publisher __ns:=/one_DOF_robot
start_background xvfb.log Xvfb "$display" -screen 0 1000x700x24
sleep 1
DISPLAY=$display LIBGL_ALWAYS_SOFTWARE=1 start_background rviz.log rviz -d docs/ros1/seed.rviz
sleep 15   # rviz starts and the arm settles at 1 rad
echo "joint1: $(rostopic echo -n 1 /one_DOF_robot/joint_states | grep position)"
DISPLAY=$display import -window root "$out"
echo "written: $out"
