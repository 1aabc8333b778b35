"""servoloop: ros_control-style robot control, simulated in-process.

    import servoloop
    with servoloop.World("robots/one_dof/one_dof_w_jnt_ctl.launch.yaml") as world:
        world.publish("/one_DOF_robot/joint1_position_controller/command", 1.0)
        world.step(2.0)
        print(world.joint_state()["position"])

See docs/python.md.
"""
from ._servoloop import ConfigError, Error, World

__all__ = ["World", "Error", "ConfigError"]
