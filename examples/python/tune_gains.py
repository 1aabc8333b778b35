"""Tune the seed robot's position gain: one World, one episode per gain
(set_param, then reset: the controller reloads with the new gain), the step
responses written as CSV and drawn by `servoloop plot`.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/tune_gains.py --out /tmp/gains
"""
import argparse
import csv
import os
import shutil
import subprocess

import numpy as np

import servoloop

HERE = os.path.dirname(os.path.abspath(__file__))
LAUNCH = os.path.join(HERE, "..", "..", "robots", "one_dof", "one_dof_w_jnt_ctl.launch.yaml")
CONTROLLER = "/one_DOF_robot/joint1_position_controller"


def step_response(world, seconds):
    """Command 1.0 rad at t = 0 and record joint1's position at 50 Hz."""
    world.subscribe("/one_DOF_robot/joint_states")  # subscribes (first call) or empties
    world.publish(CONTROLLER + "/command", 1.0)
    world.step(seconds)
    messages = world.subscribe("/one_DOF_robot/joint_states")
    return np.array([[m["stamp"], m["msg"]["position"][0]] for m in messages])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="gains", help="folder for the CSV files and the plot")
    parser.add_argument("--gains", type=float, nargs="+", default=[5.0, 10.0, 40.0, 160.0])
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    files = []
    with servoloop.World(LAUNCH) as world:
        for gain in args.gains:
            world.set_param(CONTROLLER + "/pid/p", gain)
            world.reset()
            response = step_response(world, args.seconds)
            overshoot = response[:, 1].max() - 1.0
            error = np.sqrt(np.mean((response[:, 1] - 1.0) ** 2))
            print(f"p = {gain:6.1f}: overshoot {overshoot:+.3f} rad, rms error {error:.3f} rad")
            path = os.path.join(args.out, f"p_{gain:g}.csv")
            with open(path, "w", newline="") as f:
                writer = csv.writer(f)
                writer.writerow(["time", f"p={gain:g}"])
                writer.writerows(response.tolist())
            files.append(path)

    servoloop_command = shutil.which("servoloop") or os.path.join(HERE, "..", "..", "build", "bin", "servoloop")
    plot = os.path.join(args.out, "gains.png")
    subprocess.run([servoloop_command, "plot", *files, "-o", plot, "--title", "joint1 step response by p gain"],
                   check=True)
    print(f"plot: {plot}")


if __name__ == "__main__":
    main()
