#!/usr/bin/python3
"""Calls a controller manager's services in the order ros_control's `spawner`
script calls them (that script is not packaged for Debian, so ros1_bridge_test
runs this one): wait for load_controller, switch_controller and
unload_controller; load each named controller; start the loaded ones in one
STRICT switch; spin; on shutdown stop them (STRICT) and unload them in reverse
order. Prints "started: <names>" once the switch answered ok.

usage: spawner_calls.py --namespace NS [--timeout S] NAME...
"""
import argparse
import sys

import rospy
from controller_manager_msgs.srv import LoadController, SwitchController, SwitchControllerRequest, UnloadController


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--namespace", required=True)
    parser.add_argument("--timeout", type=float, default=30.0)
    parser.add_argument("names", nargs="+")
    args = parser.parse_args(rospy.myargv()[1:])

    rospy.init_node("spawner_calls", anonymous=True)
    base = args.namespace.rstrip("/") + "/controller_manager/"
    for service in ("load_controller", "switch_controller", "unload_controller"):
        rospy.wait_for_service(base + service, timeout=args.timeout)
    load = rospy.ServiceProxy(base + "load_controller", LoadController)
    switch = rospy.ServiceProxy(base + "switch_controller", SwitchController)
    unload = rospy.ServiceProxy(base + "unload_controller", UnloadController)

    loaded = []

    def take_down():
        switch(start_controllers=[], stop_controllers=loaded, strictness=SwitchControllerRequest.STRICT,
               start_asap=False, timeout=0.0)
        for name in reversed(loaded):
            unload(name=name)
        print("taken down: " + " ".join(loaded), flush=True)

    rospy.on_shutdown(take_down)
    for name in args.names:
        if load(name=name).ok:
            loaded.append(name)
        else:
            print("failed to load " + name, flush=True)
    if not switch(start_controllers=loaded, stop_controllers=[], strictness=SwitchControllerRequest.STRICT,
                  start_asap=False, timeout=0.0).ok:
        print("failed to start " + " ".join(loaded), flush=True)
        return 1
    print("started: " + " ".join(loaded), flush=True)
    rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
