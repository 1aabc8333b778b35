#!/usr/bin/env bash
# The seed tutorial's joint servo, end to end: install what is missing, build
# only what the run needs (the `servoloop` command, the Bullet backend and the
# two controller plugins the seed loads; everything else is built by
# scripts/test.sh), then run the one-DOF robot
# with its PID position controller on the Bullet backend for 30 s of simulated
# time with a 1.0 rad command, recording the joint states and the command and
# plotting them.
#   BUILD_DIR  build folder (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja
cmake --build "$build_dir" --parallel 2 --target servoloop_main_job

out_dir="$build_dir/main_job"
mkdir -p "$out_dir"
"$build_dir/bin/servoloop" launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml --duration 30 \
  --pub /one_DOF_robot/joint1_position_controller/command:=1.0 \
  --record /one_DOF_robot/joint_states="$out_dir/joint_states.csv" \
  --record /one_DOF_robot/joint1_position_controller/command="$out_dir/command.csv" \
  --plot "$out_dir/one_dof.png"

echo "plot:        $out_dir/one_dof.png"
echo "recordings:  $out_dir/joint_states.csv"
echo "             $out_dir/command.csv"
