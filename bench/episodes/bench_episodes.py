"""Episode throughput, as users run episodes (docs/benchmarks.md, "Episodes"):

  1. one World in one thread, episodes back to back (reset, command, 5 s);
  2. `servoloop sweep` of the same episodes with --jobs 1 and --jobs 2
     (scaling efficiency = rate(jobs 2) / (2 × rate(jobs 1)));
  3. the same sweep on a 2-worker Dask cluster on loopback, against --jobs 2;
  4. World.reset() against a new World and against a new `servoloop launch`
     process for the same episode start;
  5. memory per World (resident set growth over 10 Worlds).

    PYTHONPATH=build/python /usr/bin/python3 bench/episodes/bench_episodes.py [--episodes 1000]

Prints one line per figure and writes them as JSON (--json FILE). Wall time
throughout; the machine should be otherwise idle.
"""
import argparse
import json
import os
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time

import servoloop

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SEED = os.path.join(ROOT, "robots", "one_dof", "one_dof_w_jnt_ctl.launch.yaml")
COMMAND = "/one_DOF_robot/joint1_position_controller/command"
SERVOLOOP = os.environ.get("SERVOLOOP", os.path.join(ROOT, "build", "bin", "servoloop"))


def rss_kib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def one_world_rate(episodes, duration):
    with servoloop.World(SEED) as world:
        start = time.perf_counter()
        for _ in range(episodes):
            world.reset()
            world.publish(COMMAND, 1.0)
            world.step(duration)
        return episodes / (time.perf_counter() - start)


def reset_times(count):
    with servoloop.World(SEED) as world:
        times = []
        for _ in range(count):
            world.step(0.5)
            start = time.perf_counter()
            world.reset()
            times.append(time.perf_counter() - start)
    return statistics.median(times)


def new_world_time(count):
    times = []
    for _ in range(count):
        start = time.perf_counter()
        world = servoloop.World(SEED)
        times.append(time.perf_counter() - start)
        world.close()
    return statistics.median(times)


def new_process_time(count):
    """A whole `servoloop launch` of one step: process start to exit."""
    times = []
    for _ in range(count):
        start = time.perf_counter()
        subprocess.run([SERVOLOOP, "launch", SEED, "--duration", "0.001", "--rtf", "0"], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def memory_per_world(count):
    before = rss_kib()
    worlds = [servoloop.World(SEED) for _ in range(count)]
    for world in worlds:
        world.step(0.1)
    after = rss_kib()
    for world in worlds:
        world.close()
    return (after - before) / count / 1024.0


def write_spec(folder, episodes, duration):
    spec = os.path.join(folder, "bench.sweep.yaml")
    with open(spec, "w") as f:
        f.write(f"launch: {SEED}\nduration: {duration}\n")
        f.write(f"publish: [{{topic: {COMMAND}, value: 1.0, time: 0.0}}]\n")
        f.write("random:\n  /one_DOF_robot/joint1_position_controller/pid/p: {uniform: [5.0, 20.0]}\n")
        f.write(f"samples: {episodes}\nseed: 1\n")
        f.write("measure:\n  final_q: {topic: /one_DOF_robot/joint_states, field: \"position[0]\", reduce: last}\n")
    return spec


def sweep_rate(spec, out, extra):
    env = dict(os.environ)
    start = time.perf_counter()
    subprocess.run([SERVOLOOP, "sweep", spec, "--out", out, *extra], check=True, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    with open(os.path.join(out, "episodes.csv")) as f:
        rows = sum(1 for _ in f) - 1
    return rows / wall


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def dask_rate(spec, out, workers):
    port = free_port()
    env = dict(os.environ)
    processes = [subprocess.Popen(["/usr/bin/dask-scheduler", "--host", "127.0.0.1", "--port", str(port),
                                   "--no-dashboard"], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    address = f"tcp://127.0.0.1:{port}"
    try:
        for n in range(workers):
            processes.append(subprocess.Popen(["/usr/bin/dask-worker", address, "--nworkers", "1", "--nthreads", "1",
                                               "--no-dashboard", "--name", f"w{n}"], env=env,
                                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        import distributed
        deadline = time.monotonic() + 60
        while True:
            try:
                with distributed.Client(address, timeout=5) as client:
                    client.wait_for_workers(workers, timeout=max(1, deadline - time.monotonic()))
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
        return sweep_rate(spec, out, ["--scheduler", address])
    finally:
        for process in reversed(processes):
            process.send_signal(signal.SIGTERM)
        for process in processes:
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=1000)
    parser.add_argument("--duration", type=float, default=5.0)
    parser.add_argument("--json", help="write the figures here")
    args = parser.parse_args()
    figures = {"episodes": args.episodes, "duration_s": args.duration}
    folder = tempfile.mkdtemp(prefix="servoloop-bench-episodes-")
    try:
        figures["one_world_rate"] = one_world_rate(max(50, args.episodes // 10), args.duration)
        spec = write_spec(folder, args.episodes, args.duration)
        figures["sweep_jobs1_rate"] = sweep_rate(spec, os.path.join(folder, "jobs1"), ["--jobs", "1"])
        figures["sweep_jobs2_rate"] = sweep_rate(spec, os.path.join(folder, "jobs2"), ["--jobs", "2"])
        figures["scaling_efficiency"] = figures["sweep_jobs2_rate"] / (2 * figures["sweep_jobs1_rate"])
        figures["dask2_rate"] = dask_rate(spec, os.path.join(folder, "dask2"), 2)
        figures["dask2_vs_jobs2"] = figures["dask2_rate"] / figures["sweep_jobs2_rate"]
        figures["reset_s"] = reset_times(200)
        figures["new_world_s"] = new_world_time(20)
        figures["new_process_s"] = new_process_time(10)
        figures["memory_per_world_mib"] = memory_per_world(10)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print(f"{args.episodes} episodes of {args.duration} s (seed robot, bullet, 1 kHz), wall time:")
    print(f"  one World, reset + step, back to back : {figures['one_world_rate']:8.1f} episodes/s")
    print(f"  servoloop sweep --jobs 1               : {figures['sweep_jobs1_rate']:8.1f} episodes/s")
    print(f"  servoloop sweep --jobs 2               : {figures['sweep_jobs2_rate']:8.1f} episodes/s"
          f"  (scaling efficiency {figures['scaling_efficiency']:.3f})")
    print(f"  servoloop sweep, Dask, 2 workers       : {figures['dask2_rate']:8.1f} episodes/s"
          f"  ({figures['dask2_vs_jobs2']:.3f} x --jobs 2)")
    print(f"  World.reset()                          : {figures['reset_s'] * 1e3:8.3f} ms (median of 200)")
    print(f"  a new World                            : {figures['new_world_s'] * 1e3:8.3f} ms (median of 20)")
    print(f"  a new servoloop launch process, 1 step : {figures['new_process_s'] * 1e3:8.3f} ms (median of 10)")
    print(f"  memory per World                       : {figures['memory_per_world_mib']:8.2f} MiB")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(figures, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
