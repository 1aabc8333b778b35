"""`servoloop sweep` (python -m servoloop.sweep), run as users run it: its rows
against single episodes run here with servoloop.World and reduced with numpy,
its random draws against numpy's generator, its spec checks, failed episodes,
--resume and Ctrl-C, and runs on a Dask cluster (a scheduler and two workers
started on loopback by the test) against local runs, including one whose
worker is killed mid-sweep."""
import csv
import json
import math
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest
import warnings

import numpy as np
import yaml

import servoloop

SOURCE = os.environ["SERVOLOOP_SOURCE_DIR"]
SEED = os.path.join(SOURCE, "robots", "one_dof", "one_dof_w_jnt_ctl.launch.yaml")
EXAMPLE = os.path.join(SOURCE, "examples", "sweeps", "one_dof_gains.sweep.yaml")
COMMAND = "/one_DOF_robot/joint1_position_controller/command"
JOINT_STATES = "/one_DOF_robot/joint_states"
STATE = "/one_DOF_robot/joint1_position_controller/state"
CONTROLLER = "/one_DOF_robot/joint1_position_controller"
P_GAIN = CONTROLLER + "/pid/p"
D_GAIN = CONTROLLER + "/pid/d"
FIXED = ["worker", "wall_time_s", "error"]

try:
    import distributed
except ImportError:  # Dask's tests are skipped without it
    distributed = None


def spec_of(duration=0.5, vary=None, measure=None, **more):
    """A spec for the seed robot: a unit step command at t = 0."""
    spec = {"launch": SEED, "duration": duration, "publish": [{"topic": COMMAND, "value": 1.0, "time": 0.0}]}
    if vary is not None:
        spec["vary"] = vary
    spec["measure"] = measure or {"final_q": {"topic": JOINT_STATES, "field": "position[0]", "reduce": "last"}}
    spec.update(more)
    return spec


def write_spec(directory, spec, name="sweep.yaml"):
    path = os.path.join(directory, name)
    with open(path, "w", encoding="utf-8") as stream:
        yaml.safe_dump(spec, stream, sort_keys=False)
    return path


def sweep_command(spec_path, out, *args):
    return [sys.executable, "-m", "servoloop.sweep", spec_path, "--out", out, *args]


def run_sweep(spec_path, out, *args, timeout=300):
    return subprocess.run(sweep_command(spec_path, out, *args), capture_output=True, text=True, timeout=timeout)


def read_csv(out):
    """(header, rows as dicts) of out/episodes.csv."""
    with open(os.path.join(out, "episodes.csv"), newline="", encoding="utf-8") as stream:
        reader = csv.reader(stream)
        header = next(reader)
        return header, [dict(zip(header, cells)) for cells in reader]


def data_rows(out):
    """How many episode rows out/episodes.csv holds (0 when there is none)."""
    path = os.path.join(out, "episodes.csv")
    if not os.path.isfile(path):
        return 0
    with open(path, newline="", encoding="utf-8") as stream:
        return max(sum(1 for _ in csv.reader(stream)) - 1, 0)


def wait_for(condition, timeout, what):
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        time.sleep(0.02)


def direct_messages(params, duration, topics):
    """The messages on `topics` in one episode run here: subscribe, publish
    the command at t = 0, step the duration."""
    with servoloop.World(SEED, params=params) as world:
        for topic in topics:
            world.subscribe(topic)
        world.publish(COMMAND, 1.0)
        world.step(duration)
        return {topic: world.subscribe(topic) for topic in topics}


def measures_of(rows, names):
    return [[row[name] for name in names] for row in rows]


class Cluster:
    """A Dask scheduler and workers on loopback, each in its own process."""

    def __init__(self, directory, workers=("w1", "w2")):
        self.directory = directory
        self.processes = {}
        scheduler_file = os.path.join(directory, "scheduler.json")
        self._start("scheduler", [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                                  "--port", "0", "--no-dashboard", "--scheduler-file", scheduler_file])
        wait_for(lambda: self._alive("scheduler") and os.path.exists(scheduler_file)
                 and os.path.getsize(scheduler_file) > 0, 60, "the Dask scheduler's address")
        with open(scheduler_file, encoding="utf-8") as stream:
            self.address = json.load(stream)["address"]
        for name in workers:
            # No nanny: the process killed is the worker itself.
            self._start(name, [sys.executable, "-m", "distributed.cli.dask_worker", self.address, "--nthreads", "1",
                               "--no-nanny", "--no-dashboard", "--name", name,
                               "--local-directory", os.path.join(directory, name)])
        with warnings.catch_warnings():
            # This tornado warns about what distributed does; nothing here to act on.
            warnings.simplefilter("ignore", DeprecationWarning)
            client = distributed.Client(self.address, timeout=30, set_as_default=False)
        with client:
            wait_for(lambda: len(client.scheduler_info()["workers"]) == len(workers), 60,
                     f"{len(workers)} Dask workers to join")

    def _start(self, name, command):
        log = open(os.path.join(self.directory, f"{name}.log"), "w", encoding="utf-8")
        self.processes[name] = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                                                cwd=self.directory)
        log.close()

    def _alive(self, name):
        if self.processes[name].poll() is not None:
            with open(os.path.join(self.directory, f"{name}.log"), encoding="utf-8") as stream:
                raise AssertionError(f"dask {name} exited: {stream.read()[-2000:]}")
        return True

    def kill(self, name):
        self.processes[name].send_signal(signal.SIGKILL)
        self.processes[name].wait(timeout=30)

    def stop(self):
        for process in self.processes.values():
            if process.poll() is None:
                process.terminate()
        for process in self.processes.values():
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait(timeout=15)


class SweepTest(unittest.TestCase):
    def setUp(self):
        scratch = tempfile.TemporaryDirectory(prefix="servoloop-sweep-test-")
        self.addCleanup(scratch.cleanup)
        self.dir = scratch.name

    def out(self, name):
        return os.path.join(self.dir, name)

    def assert_ran(self, done, status=0):
        self.assertEqual(done.returncode, status, f"stdout: {done.stdout}\nstderr: {done.stderr}")

    @unittest.skipUnless(os.environ.get("SERVOLOOP_CLI"), "needs SERVOLOOP_CLI (the servoloop executable)")
    def test_a_sweeps_rows_equal_single_servoloop_launches(self):
        # Each gain run by hand as a user would: `servoloop launch` with the
        # gain in a parameter file, the command at t = 0, joint states
        # recorded; the recording's last position is the row's final_q.
        gains = [5.0, 40.0]
        spec = write_spec(self.dir, spec_of(duration=1.0, vary={P_GAIN: gains}))
        out = self.out("against-launch")
        self.assert_ran(run_sweep(spec, out, "--jobs", "1"))
        _, rows = read_csv(out)
        with open(SEED, encoding="utf-8") as stream:
            seed = yaml.safe_load(stream)
        for gain, row in zip(gains, rows):
            gain_file = os.path.join(self.dir, f"gain_{gain}.yaml")
            with open(gain_file, "w", encoding="utf-8") as stream:
                stream.write(f"one_DOF_robot: {{joint1_position_controller: {{pid: {{p: {gain!r}}}}}}}\n")
            robot = dict(seed["robots"][0])
            robot["urdf"] = os.path.join(os.path.dirname(SEED), robot["urdf"])
            robot["params"] = [os.path.join(os.path.dirname(SEED), f) for f in robot["params"]] + [gain_file]
            launch = os.path.join(self.dir, f"gain_{gain}.launch.yaml")
            with open(launch, "w", encoding="utf-8") as stream:
                yaml.safe_dump({**seed, "robots": [robot]}, stream, sort_keys=False)
            recording = os.path.join(self.dir, f"gain_{gain}.csv")
            done = subprocess.run([os.environ["SERVOLOOP_CLI"], "launch", launch, "--duration", "1.0",
                                   "--pub", f"{COMMAND}:=1.0", "--record", f"{JOINT_STATES}={recording}"],
                                  capture_output=True, text=True, timeout=120)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(recording, newline="", encoding="utf-8") as stream:
                recorded = list(csv.DictReader(stream))
            self.assertEqual(len(recorded), 50)
            self.assertEqual(float(row["final_q"]), float(recorded[-1]["joint1.position"]))

    def test_a_parameter_read_at_start_gives_each_episode_a_new_world(self):
        # A robot's simulation setting (read when its hardware starts, not by
        # a controller): each episode must start from its own value, also
        # when one thread runs them all.
        params = os.path.join(self.dir, "start.yaml")
        with open(params, "w", encoding="utf-8") as stream:
            stream.write("one_DOF_robot: {sim: {initial_positions: {joint1: 0.0}}}\n")
        launch = os.path.join(self.dir, "start.launch.yaml")
        with open(SEED, encoding="utf-8") as stream:
            seed = yaml.safe_load(stream)
        robot = seed["robots"][0]
        robot["urdf"] = os.path.join(os.path.dirname(SEED), robot["urdf"])
        robot["params"] = [os.path.join(os.path.dirname(SEED), file) for file in robot["params"]] + [params]
        with open(launch, "w", encoding="utf-8") as stream:
            yaml.safe_dump(seed, stream, sort_keys=False)
        starts = [0.0, 0.5, 1.25]
        measure = {"first_q": {"topic": JOINT_STATES, "field": "position[0]", "reduce": "first"}}
        spec = write_spec(self.dir, spec_of(duration=0.1, measure=measure, launch=launch,
                                            vary={"/one_DOF_robot/sim/initial_positions/joint1": starts}))
        out = self.out("starts")
        self.assert_ran(run_sweep(spec, out, "--jobs", "1"))
        _, rows = read_csv(out)
        self.assertEqual([float(row["first_q"]) for row in rows], starts)

    def test_a_grids_rows_are_the_episodes_run_one_by_one(self):
        gains = [5.0, 10.0, 20.0]
        measure = {"final_q": {"topic": JOINT_STATES, "field": "position[0]", "reduce": "last"},
                   "peak_q": {"topic": JOINT_STATES, "field": "position[0]", "reduce": "max"}}
        spec = write_spec(self.dir, spec_of(duration=1.0, vary={P_GAIN: gains}, measure=measure))
        # One thread runs every episode in one World (set_param and reset);
        # two threads each build their own: both give the fresh runs' rows.
        for jobs in ("1", "2"):
            with self.subTest(jobs=jobs):
                self.check_grid_rows(spec, self.out(f"grid{jobs}"), jobs, gains)

    def check_grid_rows(self, spec, out, jobs, gains):
        self.assert_ran(run_sweep(spec, out, "--jobs", jobs))
        header, rows = read_csv(out)
        self.assertEqual(header, ["id", P_GAIN, "repeat", "final_q", "peak_q", *FIXED])
        self.assertEqual([row["id"] for row in rows], ["0", "1", "2"])
        for gain, row in zip(gains, rows):
            self.assertEqual(float(row[P_GAIN]), gain)
            self.assertEqual(row["repeat"], "0")
            self.assertEqual(row["error"], "")
            self.assertTrue(row["worker"])
            self.assertGreater(float(row["wall_time_s"]), 0.0)
            messages = direct_messages({P_GAIN: gain}, 1.0, [JOINT_STATES])[JOINT_STATES]
            positions = [m["msg"]["position"][0] for m in messages]
            self.assertEqual(len(positions), 50)
            self.assertEqual(float(row["final_q"]), positions[-1])
            self.assertEqual(float(row["peak_q"]), np.max(positions))
        # The gains make different episodes (else equality above proves little).
        self.assertEqual(len({row["final_q"] for row in rows}), 3)
        if os.path.exists("/usr/bin/gnuplot"):
            for name in ("final_q", "peak_q"):
                path = os.path.join(out, "plots", f"{name}_vs_one_DOF_robot_joint1_position_controller_pid_p.png")
                with open(path, "rb") as stream:
                    self.assertEqual(stream.read(8), b"\x89PNG\r\n\x1a\n")

    def test_each_reduce_is_numpys_over_the_episodes_messages(self):
        reduces = ["first", "last", "min", "max", "mean", "rms"]
        measure = {f"q_{how}": {"topic": JOINT_STATES, "field": "position[0]", "reduce": how} for how in reduces}
        measure["error_rms"] = {"topic": STATE, "field": "error", "reduce": "rms"}
        spec = write_spec(self.dir, spec_of(duration=1.0, measure=measure))
        out = self.out("reduce")
        self.assert_ran(run_sweep(spec, out))
        _, rows = read_csv(out)
        self.assertEqual(len(rows), 1)
        row = rows[0]
        messages = direct_messages({}, 1.0, [JOINT_STATES, STATE])
        q = np.array([m["msg"]["position"][0] for m in messages[JOINT_STATES]])
        error = np.array([m["msg"]["error"] for m in messages[STATE]])
        self.assertEqual(float(row["q_first"]), q[0])
        self.assertEqual(float(row["q_last"]), q[-1])
        self.assertEqual(float(row["q_min"]), q.min())
        self.assertEqual(float(row["q_max"]), q.max())
        self.assertTrue(math.isclose(float(row["q_mean"]), q.mean(), rel_tol=1e-12))
        self.assertTrue(math.isclose(float(row["q_rms"]), math.sqrt(np.sum(q * q) / len(q)), rel_tol=1e-12))
        self.assertTrue(math.isclose(float(row["error_rms"]), math.sqrt(np.sum(error * error) / len(error)),
                                     rel_tol=1e-12))
        self.assertGreater(q.max(), q[0])  # the joint moved: min, max and mean differ

    def test_random_samples_come_from_the_seed_and_repeats_repeat(self):
        random = {D_GAIN: {"uniform": [1.0, 20.0]}}
        spec = write_spec(self.dir, spec_of(random=random, samples=4, seed=3))
        first, second = self.out("first"), self.out("second")
        self.assert_ran(run_sweep(spec, first))
        self.assert_ran(run_sweep(spec, second))
        _, rows = read_csv(first)
        _, again = read_csv(second)
        self.assertEqual([row["id"] for row in rows], ["0", "1", "2", "3"])
        draws = [float(row[D_GAIN]) for row in rows]
        generator = np.random.default_rng(3)
        self.assertEqual(draws, [generator.uniform(1.0, 20.0) for _ in range(4)])
        self.assertTrue(all(1.0 <= d < 20.0 for d in draws))
        self.assertEqual(measures_of(rows, [D_GAIN, "final_q"]), measures_of(again, [D_GAIN, "final_q"]))
        self.assertEqual(len({row["final_q"] for row in rows}), 4)

        repeated = write_spec(self.dir, spec_of(random=random, samples=4, seed=3, repeat=2), "repeat.yaml")
        twice = self.out("twice")
        self.assert_ran(run_sweep(repeated, twice))
        _, doubled = read_csv(twice)
        self.assertEqual([row["id"] for row in doubled], [str(i) for i in range(8)])
        for index, row in enumerate(rows):
            pair = doubled[2 * index: 2 * index + 2]
            self.assertEqual([r["repeat"] for r in pair], ["0", "1"])
            self.assertEqual(measures_of(pair, [D_GAIN, "final_q"]), [[row[D_GAIN], row["final_q"]]] * 2)

    def test_bad_specs_are_refused_before_any_episode_with_the_closest_name(self):
        q = {"topic": JOINT_STATES, "field": "position[0]"}
        cases = {
            "param.yaml": (spec_of(vary={CONTROLLER + "/pid/pp": [1.0]}), [CONTROLLER + "/pid/pp", P_GAIN]),
            "topic.yaml": (spec_of(measure={"q": {**q, "topic": "/one_DOF_robot/joint_state"}}),
                           ["/one_DOF_robot/joint_state", JOINT_STATES]),
            "field.yaml": (spec_of(measure={"q": {**q, "field": "positon[0]"}}), ["positon", "position"]),
            "reduce.yaml": (spec_of(measure={"q": {**q, "reduce": "meen"}}), ["meen", "mean"]),
            "key.yaml": ({**spec_of(vary={P_GAIN: [1.0]}), "varyy": {P_GAIN: [2.0]}}, ["varyy", "'vary'"]),
        }
        for name, (spec, expected) in cases.items():
            with self.subTest(name):
                out = self.out(name + ".out")
                done = run_sweep(write_spec(self.dir, spec, name), out)
                self.assert_ran(done, 2)
                self.assertIn(name, done.stderr)
                for text in expected:
                    self.assertIn(text, done.stderr)
                self.assertEqual(data_rows(out), 0)

    def test_a_failing_episode_is_a_row_with_its_error_and_the_others_run(self):
        measure = {"final_q": {"topic": JOINT_STATES, "field": "position[0]", "reduce": "last"}}
        spec = write_spec(self.dir, spec_of(vary={CONTROLLER + "/joint": ["joint1", "no_such_joint"]},
                                            measure=measure))
        out = self.out("failing")
        done = run_sweep(spec, out)
        self.assert_ran(done, 1)  # the module's convention: 1 when some episode failed
        _, rows = read_csv(out)
        self.assertEqual([row["id"] for row in rows], ["0", "1"])
        good, bad = rows
        self.assertEqual(good["error"], "")
        positions = direct_messages({}, 0.5, [JOINT_STATES])[JOINT_STATES]
        self.assertEqual(float(good["final_q"]), positions[-1]["msg"]["position"][0])
        # Its controller did not load, so the command topic it publishes on is missing.
        self.assertIn(COMMAND, bad["error"])
        self.assertEqual(bad["final_q"], "")
        self.assertNotIn("\n", bad["error"])

    def test_resume_runs_only_the_missing_episodes(self):
        spec_path = write_spec(self.dir, spec_of(vary={P_GAIN: [4.0, 8.0, 12.0, 16.0]}))
        out = self.out("resumed")
        self.assert_ran(run_sweep(spec_path, out))
        header, full = read_csv(out)
        # Keep episode 0 (marked, to see that it is not run again), lose 1..3.
        with open(os.path.join(out, "episodes.csv"), "w", newline="", encoding="utf-8") as stream:
            writer = csv.DictWriter(stream, fieldnames=header)
            writer.writeheader()
            writer.writerow({**full[0], "worker": "kept"})

        refused = run_sweep(spec_path, out)
        self.assert_ran(refused, 2)
        self.assertIn("--resume", refused.stderr)
        self.assertEqual(data_rows(out), 1)

        changed = write_spec(self.dir, spec_of(duration=0.6, vary={P_GAIN: [4.0, 8.0, 12.0, 16.0]}))
        self.assertEqual(changed, spec_path)
        different = run_sweep(spec_path, out, "--resume")
        self.assert_ran(different, 2)
        self.assertIn("duration", different.stderr)
        self.assertEqual(data_rows(out), 1)

        write_spec(self.dir, spec_of(vary={P_GAIN: [4.0, 8.0, 12.0, 16.0]}))
        self.assert_ran(run_sweep(spec_path, out, "--resume"))
        _, resumed = read_csv(out)
        self.assertEqual([row["id"] for row in resumed], ["0", "1", "2", "3"])
        self.assertEqual(resumed[0]["worker"], "kept")
        self.assertTrue(all(row["worker"].startswith("local") for row in resumed[1:]))
        names = ["id", P_GAIN, "repeat", "final_q", "error"]
        self.assertEqual(measures_of(resumed, names), measures_of(full, names))

    def test_ctrl_c_keeps_the_finished_rows_and_resume_completes_them(self):
        spec_path = write_spec(self.dir, spec_of(duration=30.0, vary={P_GAIN: [float(p) for p in range(1, 13)]}))
        out = self.out("interrupted")
        # SIGINT as at a terminal, whatever this test inherited.
        sweep = subprocess.Popen(sweep_command(spec_path, out, "--jobs", "1"), stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True,
                                 preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        self.addCleanup(lambda: sweep.poll() is None and sweep.kill())
        wait_for(lambda: data_rows(out) >= 2 or sweep.poll() is not None, 120, "two finished episodes")
        self.assertIsNone(sweep.poll(), "the sweep ended before it could be interrupted")
        sweep.send_signal(signal.SIGINT)
        _, stderr = sweep.communicate(timeout=120)
        self.assertEqual(sweep.returncode, 130, stderr)
        self.assertIn("--resume", stderr)
        _, kept = read_csv(out)
        self.assertTrue(2 <= len(kept) < 12, f"{len(kept)} rows")
        self.assertEqual([row["id"] for row in kept], [str(i) for i in range(len(kept))])
        self.assert_ran(run_sweep(spec_path, out, "--resume", "--jobs", "2"))
        _, rows = read_csv(out)
        self.assertEqual([row["id"] for row in rows], [str(i) for i in range(12)])
        self.assertEqual(rows[:len(kept)], kept)
        self.assertTrue(all(row["error"] == "" and row["final_q"] for row in rows))

    def test_the_example_spec_is_valid_and_measures_the_controllers_error(self):
        with open(EXAMPLE, encoding="utf-8") as stream:
            example = yaml.safe_load(stream)
        # The example's own measures and grid, on a shorter episode.
        example["launch"] = SEED
        example["duration"] = 0.5
        example["vary"] = {path: values[:1] for path, values in example["vary"].items()}
        out = self.out("example")
        self.assert_ran(run_sweep(write_spec(self.dir, example), out))
        _, rows = read_csv(out)
        self.assertEqual(len(rows), 1)
        self.assertTrue(all(rows[0][name] for name in example["measure"]))


@unittest.skipIf(distributed is None, "Dask's distributed is not installed")
class DaskSweepTest(unittest.TestCase):
    def setUp(self):
        scratch = tempfile.TemporaryDirectory(prefix="servoloop-sweep-dask-test-")
        self.addCleanup(scratch.cleanup)
        self.dir = scratch.name

    def start_cluster(self):
        cluster = None

        def stop():
            if cluster is not None:
                cluster.stop()

        self.addCleanup(stop)
        cluster = Cluster(self.dir)
        return cluster

    def local_reference(self, spec_path):
        out = os.path.join(self.dir, "local")
        done = run_sweep(spec_path, out, "--jobs", "2")
        self.assertEqual(done.returncode, 0, done.stderr)
        return read_csv(out)[1]

    def test_a_dask_sweep_gives_the_local_sweeps_rows_on_both_workers(self):
        cluster = self.start_cluster()
        spec_path = write_spec(self.dir, spec_of(duration=2.0, vary={P_GAIN: [2.0 * k for k in range(1, 9)]}))
        out = os.path.join(self.dir, "dask")
        done = run_sweep(spec_path, out, "--scheduler", cluster.address)
        self.assertEqual(done.returncode, 0, done.stderr)
        header, rows = read_csv(out)
        names = ["id", P_GAIN, "repeat", "final_q", "error"]
        self.assertEqual(measures_of(rows, names), measures_of(self.local_reference(spec_path), names))
        self.assertEqual({row["worker"] for row in rows}, {"w1", "w2"})

    def test_a_killed_worker_costs_no_episode(self):
        cluster = self.start_cluster()
        spec_path = write_spec(self.dir, spec_of(duration=30.0, vary={P_GAIN: [float(p) for p in range(1, 17)]}))
        out = os.path.join(self.dir, "dask")
        sweep = subprocess.Popen(sweep_command(spec_path, out, "--scheduler", cluster.address),
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.addCleanup(lambda: sweep.poll() is None and sweep.kill())
        wait_for(lambda: data_rows(out) >= 2 or sweep.poll() is not None, 120, "two finished episodes")
        self.assertIsNone(sweep.poll(), "the sweep ended before a worker could be killed")
        cluster.kill("w1")
        rows_at_kill = data_rows(out)
        _, stderr = sweep.communicate(timeout=300)
        self.assertEqual(sweep.returncode, 0, stderr)
        self.assertLess(rows_at_kill, 16)
        _, rows = read_csv(out)
        self.assertEqual([row["id"] for row in rows], [str(i) for i in range(16)])
        names = ["id", P_GAIN, "repeat", "final_q", "error"]
        self.assertEqual(measures_of(rows, names), measures_of(self.local_reference(spec_path), names))

    def test_a_scheduler_that_does_not_answer_is_one_error(self):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            address = f"tcp://127.0.0.1:{probe.getsockname()[1]}"
        spec_path = write_spec(self.dir, spec_of())
        out = os.path.join(self.dir, "nowhere")
        start = time.monotonic()
        done = run_sweep(spec_path, out, "--scheduler", address, timeout=60)
        elapsed = time.monotonic() - start
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertIn(address, done.stderr)
        self.assertLess(elapsed, 15.0)
        self.assertEqual(data_rows(out), 0)


if __name__ == "__main__":
    unittest.main()
