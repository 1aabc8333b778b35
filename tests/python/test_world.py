"""servoloop.World: the Python package's in-process world, against
independent references (the controller's set point, the publish rate, a
fresh launch), its errors, and the GIL released while it steps."""
import math
import os
import tempfile
import threading
import unittest

import numpy as np

import servoloop

SOURCE = os.environ["SERVOLOOP_SOURCE_DIR"]
SEED = os.path.join(SOURCE, "robots", "one_dof", "one_dof_w_jnt_ctl.launch.yaml")
PUSH = os.path.join(SOURCE, "robots", "diff_bot", "push_crate.launch.yaml")
COMMAND = "/one_DOF_robot/joint1_position_controller/command"
P_GAIN = "/one_DOF_robot/joint1_position_controller/pid/p"


def positions(world, chunks=20, seconds=0.1):
    """The joint positions after each of `chunks` steps of `seconds`."""
    out = []
    for _ in range(chunks):
        world.step(seconds)
        out.append(world.joint_state()["position"].copy())
    return np.array(out)


class WorldTest(unittest.TestCase):
    def test_the_seed_robot_follows_its_position_command(self):
        with servoloop.World(SEED) as world:
            self.assertEqual(world.time, 0.0)
            self.assertEqual(world.namespaces, ["/one_DOF_robot"])
            world.publish(COMMAND, 1.0)
            self.assertEqual(world.step(30.0), 30000)
            self.assertAlmostEqual(world.time, 30.0, places=12)
            state = world.joint_state()
            self.assertEqual(state["name"], ["joint1"])
            self.assertIsInstance(state["position"], np.ndarray)
            # The PID's set point, reached (the seed's gains settle in about 20 s).
            self.assertAlmostEqual(state["position"][0], 1.0, delta=0.002)
            self.assertAlmostEqual(state["velocity"][0], 0.0, delta=0.002)
            self.assertEqual(world.step_cycles(7), 7)
            self.assertAlmostEqual(world.time, 30.007, places=12)

    def test_a_reset_world_runs_bit_identically_to_a_fresh_one(self):
        with servoloop.World(SEED) as world:
            world.publish(COMMAND, 0.8)
            first = positions(world)
            self.assertGreater(first[-1][0], 0.5)
            world.reset()
            self.assertEqual(world.time, 0.0)
            world.publish(COMMAND, 0.8)
            self.assertTrue(np.array_equal(first, positions(world)))
        with servoloop.World(SEED, backend="mujoco") as world:
            world.publish(COMMAND, 0.8)
            first = positions(world)
            world.reset()
            world.publish(COMMAND, 0.8)
            self.assertTrue(np.array_equal(first, positions(world)))

    def test_subscribe_returns_the_messages_since_the_last_call(self):
        with servoloop.World(SEED) as world:
            self.assertEqual(world.subscribe("/one_DOF_robot/joint_states"), [])
            world.step(1.0)
            messages = world.subscribe("/one_DOF_robot/joint_states")
            # joint_state_controller at 50 Hz from t = 0: 0, 0.02, ..., 0.98.
            self.assertEqual(len(messages), 50)
            stamps = [m["stamp"] for m in messages]
            self.assertTrue(np.allclose(np.diff(stamps), 0.02, atol=1e-9))
            self.assertEqual(messages[0]["type"], "sensor_msgs/JointState")
            self.assertEqual(messages[-1]["msg"]["name"], ["joint1"])
            self.assertEqual(world.subscribe("/one_DOF_robot/joint_states"), [])

    def test_a_changed_gain_takes_effect_at_the_reset_as_in_a_fresh_world_given_it(self):
        with servoloop.World(SEED) as world:
            original = world.get_param(P_GAIN)
            world.publish(COMMAND, 1.0)
            before = positions(world, 10)
            world.set_param(P_GAIN, original / 4)
            self.assertEqual(world.get_param(P_GAIN), original / 4)
            world.reset()
            world.publish(COMMAND, 1.0)
            after = positions(world, 10)
        self.assertFalse(np.array_equal(before, after), "the new gain did not change the run")
        with servoloop.World(SEED, params={P_GAIN: original / 4}) as fresh:
            fresh.publish(COMMAND, 1.0)
            self.assertTrue(np.array_equal(after, positions(fresh, 10)))

    def test_model_state_gives_a_pushed_crate_and_a_fixed_arm(self):
        with servoloop.World(PUSH) as world:
            start = world.model_state("crate")
            self.assertAlmostEqual(start["pose"]["position"]["x"], 0.8, places=6)
            world.step(6.0)
            pushed = world.model_state("/crate")
            self.assertFalse(pushed["fixed"])
            # Driven from 0.5 s at 0.3 m/s, the base reaches the crate at ~2.3 s
            # and pushes it on: about 1 m by 6 s.
            self.assertGreater(pushed["pose"]["position"]["x"], 1.5)
        with servoloop.World(SEED) as world:
            self.assertTrue(world.model_state("one_DOF_robot")["fixed"])

    def test_set_model_state_throws_the_crate_on_a_ballistic_path(self):
        """From 3 m up at (0, 1, 2) m/s: y = y0 + t, z = z0 + 2 t - g t^2 / 2,
        vz = 2 - g t (semi-implicit Euler at 1 ms: z within g t dt / 2)."""
        g, t = 9.81, 0.4
        with servoloop.World(PUSH) as world:
            state = world.model_state("crate")
            y0 = state["pose"]["position"]["y"]
            state["pose"]["position"]["z"] = 3.0
            state["twist"]["linear"] = {"x": 0.0, "y": 1.0, "z": 2.0}
            thrown = world.set_model_state("crate", pose=state["pose"], twist=state["twist"])
            self.assertEqual(thrown["pose"]["position"]["z"], 3.0)
            world.step(t)
            flown = world.model_state("crate")
            self.assertAlmostEqual(flown["pose"]["position"]["y"], y0 + 1.0 * t, delta=1e-6)
            self.assertAlmostEqual(flown["pose"]["position"]["z"], 3.0 + 2.0 * t - g * t * t / 2, delta=3e-3)
            self.assertAlmostEqual(flown["twist"]["linear"]["z"], 2.0 - g * t, delta=1e-6)
            # Only a twist: the pose stays where the flight took it.
            still = world.set_model_state("crate", twist={"linear": {"x": 0, "y": 0, "z": 0},
                                                          "angular": {"x": 0, "y": 0, "z": 0}})
            self.assertEqual(still["pose"]["position"]["z"], flown["pose"]["position"]["z"])
            with self.assertRaises(servoloop.Error) as bad:
                world.set_model_state("crate", twist={"linear": {"x": 1, "y": 0}})
            self.assertIn("twist.linear.z", str(bad.exception))
        with servoloop.World(SEED) as world:
            with self.assertRaises(servoloop.Error) as fixed:
                world.set_model_state("one_DOF_robot", pose={"position": {"x": 0, "y": 0, "z": 1},
                                                              "orientation": {"x": 0, "y": 0, "z": 0, "w": 1}})
            self.assertIn("fixed base", str(fixed.exception))

    def test_errors_are_python_exceptions_with_the_command_lines_text(self):
        with self.assertRaises(servoloop.ConfigError) as missing:
            servoloop.World(os.path.join(tempfile.gettempdir(), "no-such.launch.yaml"))
        self.assertIn("no-such.launch.yaml", str(missing.exception))
        with servoloop.World(SEED) as world:
            with self.assertRaises(servoloop.Error) as wrong:
                world.joint_state("/nobody")
            self.assertIn("/one_DOF_robot", str(wrong.exception))
            with self.assertRaises(servoloop.Error):
                world.step(-1.0)
            with self.assertRaises(servoloop.Error) as bad:
                world.publish(COMMAND, {"no_such_field": 1.0})
            self.assertIn("no_such_field", str(bad.exception))
            with self.assertRaises(ValueError):
                world.publish(COMMAND, math.nan)
            world.step(0.1)  # and the world runs on
            self.assertAlmostEqual(world.time, 0.1, places=12)
        world.close()
        with self.assertRaises(servoloop.Error):
            world.step(0.1)

    def test_the_gil_is_released_while_a_world_steps(self):
        with servoloop.World(SEED) as world:
            done = threading.Event()
            result = {}

            def run():
                result["steps"] = world.step(60.0)
                done.set()

            thread = threading.Thread(target=run)
            counted = 0
            refused = None
            thread.start()
            while not done.is_set():
                counted += 1
                if refused is None and world.time > 0.0:
                    # One World, one thread at a time: a second call is refused.
                    try:
                        world.step_cycles(1)
                        refused = "accepted"
                    except servoloop.Error as e:
                        refused = str(e)
            thread.join()
            self.assertEqual(result["steps"], 60000)
            # Python ran here all along; with the GIL held it could not have.
            self.assertGreater(counted, 1000)
            self.assertIn("in use by another thread", refused)

    def test_worlds_in_two_threads_give_what_each_gives_alone(self):
        def episode(gain, out, key):
            with servoloop.World(SEED, params={P_GAIN: gain}) as world:
                world.publish(COMMAND, 1.0)
                out[key] = positions(world, 10)

        alone = {}
        episode(50.0, alone, "a")
        episode(200.0, alone, "b")
        together = {}
        threads = [threading.Thread(target=episode, args=(50.0, together, "a")),
                   threading.Thread(target=episode, args=(200.0, together, "b"))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        self.assertTrue(np.array_equal(alone["a"], together["a"]))
        self.assertTrue(np.array_equal(alone["b"], together["b"]))


if __name__ == "__main__":
    unittest.main()
