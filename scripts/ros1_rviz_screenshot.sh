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
scratch=$(mktemp -d /tmp/servoloop-rviz.XXXXXX)
export SERVOLOOP_RUN_DIR="$scratch/run" ROS_HOME="$scratch/ros" ROS_LOG_DIR="$scratch/ros/log" ROS_HOSTNAME=localhost
mkdir -p "$SERVOLOOP_RUN_DIR" && chmod 700 "$SERVOLOOP_RUN_DIR"
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://localhost:$port"
display=:$(( 90 + RANDOM % 9 ))
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  sleep 2
  for pid in "${pids[@]}"; do kill -KILL -- "-$pid" 2>/dev/null || kill -KILL "$pid" 2>/dev/null || true; done
  rm -rf "$scratch"
}
trap cleanup EXIT

setsid roscore -p "$port" > "$scratch/roscore.log" 2>&1 & pids+=($!)
until rosparam get /rosdistro > /dev/null 2>&1; do sleep 0.2; done
"$bin/servoloop" launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml --rtf 1 --ros1-bridge \
  --pub /one_DOF_robot/joint1_position_controller/command:=1.0 > "$scratch/node.log" 2>&1 & pids+=($!)
until rostopic list 2>/dev/null | grep -q /one_DOF_robot/joint_states; do sleep 0.2; done
/usr/lib/robot_state_publisher/robot_state_publisher __ns:=/one_DOF_robot > "$scratch/rsp.log" 2>&1 & pids+=($!)
Xvfb "$display" -screen 0 1000x700x24 > "$scratch/xvfb.log" 2>&1 & pids+=($!)
sleep 1
DISPLAY=$display LIBGL_ALWAYS_SOFTWARE=1 rviz -d docs/ros1/seed.rviz > "$scratch/rviz.log" 2>&1 & pids+=($!)
sleep 15   # rviz starts and the arm settles at 1 rad
echo "joint1: $(rostopic echo -n 1 /one_DOF_robot/joint_states | grep position)"
DISPLAY=$display import -window root "$out"
echo "written: $out"
