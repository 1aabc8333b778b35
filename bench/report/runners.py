"""The benchmarks behind docs/benchmarks.md: each function runs one of them and
returns its figures as rows (figure, value, target, conditions); the driver
(benchmarks_report.py) stamps every row with the time and commit it was
measured at. Figures are medians; ratios are taken within one run.

A runner that cannot run (no MuJoCo, no cyclictest, no ROS 1, no valgrind)
raises Skipped with the reason; the page then says what was not measured.
"""
import json
import os
import re
import shutil
import statistics
import subprocess
import tempfile
import time

from process_timing import paired, wall_and_cpu


class Skipped(Exception):
    """A benchmark that this machine or build cannot run; the message says why."""


class Context:
    def __init__(self, root, bin_dir, results_dir, quick):
        self.root, self.bin, self.results, self.quick = root, bin_dir, results_dir, quick

    def exe(self, name):
        path = os.path.join(self.bin, name)
        if not os.access(path, os.X_OK):
            raise Skipped(f"{name} is not built")
        return path

    def run(self, command, log_name, env=None, cwd=None, timeout=3600):
        """Runs a command, keeps its output in the results folder, returns stdout."""
        full_env = dict(os.environ, **(env or {}))
        result = subprocess.run(command, cwd=cwd or self.root, env=full_env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, timeout=timeout)
        with open(os.path.join(self.results, log_name), "w") as log:
            log.write(f"$ {' '.join(command)}\n{result.stdout}\n--- stderr ---\n{result.stderr}")
        if result.returncode != 0:
            raise RuntimeError(f"{' '.join(command)} exited with {result.returncode}; see {log_name}")
        return result.stdout


def row(figure, value, conditions, target="—"):
    return {"figure": figure, "value": value, "target": target, "conditions": conditions}


def verdict(met):
    return "met" if met else "NOT met"


def median(values):
    return statistics.median(values)


def _benchmark_medians(path):
    """Median thread CPU time (ns) of each benchmark in a Google Benchmark JSON report, over its repetitions."""
    with open(path) as f:
        report = json.load(f)
    times = {}
    for entry in report["benchmarks"]:
        if entry.get("run_type") == "iteration":
            times.setdefault(entry["run_name"], []).append(entry["cpu_time"])
    return {name: median(values) for name, values in times.items()}


# --- 1. the controller manager ---------------------------------------------------------------

MANAGER_FILTER = ("manager/(empty|per_joint|per_joint_timed|group|trajectory|joint_states_only|diff_drive)/"
                  "(jsc_50Hz/)?joints|manager/per_joint/jsc_every_cycle/joints:1$")


def manager(ctx):
    repetitions = 3 if ctx.quick else 9
    out = os.path.join(ctx.results, "controller_manager.json")
    ctx.run([ctx.exe("servoloop_bench_controller_manager"), f"--benchmark_filter={MANAGER_FILTER}",
             f"--benchmark_repetitions={repetitions}", f"--benchmark_min_time={0.02 if ctx.quick else 0.1}",
             "--benchmark_enable_random_interleaving=true", f"--benchmark_out={out}",
             "--benchmark_out_format=json"], "controller_manager.txt")
    ns = _benchmark_medians(out)

    def get(kind, joints, jsc="jsc_50Hz"):
        return ns[f"manager/{kind}/{jsc}/joints:{joints}"]

    empty = ns["manager/empty/joints:1"]
    conditions = (f"`servoloop_bench_controller_manager`, thread CPU time, median of {repetitions} interleaved "
                  "repetitions; a RobotHW whose read and write do nothing, controllers loaded as a node loads them")
    rows = []
    for kind, label in (("per_joint", "no timing (a bare manager)"),
                        ("per_joint_timed", "updates timed as the node's loops sample them (one cycle in 16)")):
        one, eight, sixty_four = get(kind, 1), get(kind, 8), get(kind, 64)
        per_joint = (sixty_four - one) / 63
        ros_control = all(get(kind, n) < 100 + 75 * (n - 1) for n in (1, 2, 4, 8, 16, 32, 64))
        target_met = one <= 30 and per_joint <= 25
        rows.append(row(
            f"Manager cost per cycle, one JointPositionController per joint + JointStateController at 50 Hz, "
            f"{label}: 1 / 8 / 64 joints",
            f"{one:.1f} / {eight:.0f} / {sixty_four:,.0f} ns; {per_joint:.1f} ns per added joint; "
            f"{one / empty:.1f} × the empty manager",
            conditions,
            f"≤ 30 ns for 1 joint and ≤ 25 ns per joint: {verdict(target_met)}; under ros_control's "
            f"(about 100 ns + 75 ns per joint) at 1–64 joints: {verdict(ros_control)}"))
    rows.append(row("Empty controller manager", f"{empty:.1f} ns", conditions))
    rows.append(row("JointStateController alone at 50 Hz: 1 / 8 / 64 joints",
                    " / ".join(f"{get('joint_states_only', n):.1f}" for n in (1, 8, 64)) + " ns", conditions))
    rows.append(row("JointStateController publishing every cycle instead of at 50 Hz, 1 joint with a position "
                    "controller",
                    f"{get('per_joint', 1, 'jsc_every_cycle'):.0f} ns instead of {get('per_joint', 1):.0f} ns", conditions))
    rows.append(row("One JointGroupPositionController: 1 / 8 / 64 joints",
                    " / ".join(f"{get('group', n):,.0f}" for n in (1, 8, 64)) + " ns", conditions))
    rows.append(row("JointTrajectoryController mid-trajectory: 1 / 6 / 64 joints",
                    " / ".join(f"{get('trajectory', n):,.0f}" for n in (1, 6, 64)) +
                    f" ns; 6 joints: {get('trajectory', 6) / get('group', 6):.1f} × a group position controller",
                    conditions))
    rows.append(row("DiffDriveController, two wheels (odometry every cycle, `odom` and `/tf` at 50 Hz)",
                    f"{get('diff_drive', 2):.0f} ns", conditions))
    return rows


# --- 2 and 5. the whole loop in process against the raw engine --------------------------------

def _loop(ctx, exe_name, engine, log_name):
    repetitions = 3 if ctx.quick else 21
    out = os.path.join(ctx.results, log_name.replace(".txt", ".json"))
    text = ctx.run([ctx.exe(exe_name), f"--benchmark_repetitions={repetitions}",
                    "--benchmark_enable_random_interleaving=true", f"--benchmark_out={out}",
                    "--benchmark_out_format=json"], log_name)
    paired_ratios = {m.group(1): (float(m.group(2)), int(m.group(3)))
              for m in re.finditer(r"^\s+(\S+): paired\s+([0-9.]+) median of (\d+) pairs", text, re.M)}
    ns = _benchmark_medians(out)
    conditions = (f"`{exe_name}`, thread CPU time; {repetitions} interleaved repetitions, each one episode on a "
                  "fresh robot; paired: a raw and a servoloop episode back to back in alternating order, the "
                  "median of the per-pair ratios")
    rows = []
    for robot in ("seed", "chain32", "chain32_group"):
        if robot in paired_ratios:
            ratio, pairs = paired_ratios[robot]
            rows.append(row(f"Whole loop in process ÷ raw {engine} stepping with the control law inline, {robot}",
                            f"{ratio:.3f} ({pairs} pairs)", conditions, "≤ 1.10: " + verdict(ratio <= 1.10)))
    ratios = {m.group(1): float(m.group(2)) for m in re.finditer(
        r"^\s+(\S+): \(a\) servoloop\+mujoco / raw mujoco\s+[0-9.]+ wall\s+([0-9.]+) thread CPU", text, re.M)}
    if ratios:
        rows.append(row("Whole loop in process ÷ raw MuJoCo stepping: seed / chain32 (ratio of medians)",
                        " / ".join(f"{ratios[r]:.3f}" for r in ("seed", "chain32") if r in ratios), conditions))
    versus = {m.group(1): float(m.group(2)) for m in re.finditer(
        r"^\s+(\S+): \(b\) raw bullet / raw mujoco\s+[0-9.]+ wall\s+([0-9.]+) thread CPU", text, re.M)}
    if versus:
        rows.append(row("Raw Bullet ÷ raw MuJoCo per step, as servoloop configures them (MuJoCo with RK4): seed / "
                        "chain32", " / ".join(f"{versus[r]:.3f}" for r in ("seed", "chain32") if r in versus),
                        conditions))
    steps = {"seed": 10000, "chain32": 2000, "chain32_group": 2000}
    mock = [f"{ns[f'loop/{r}/servoloop_mock/iterations:1'] / steps[r]:,.0f}"
            for r in steps if f"loop/{r}/servoloop_mock/iterations:1" in ns]
    if mock and engine == "Bullet":
        rows.append(row("The framework alone (mock backend), per step: seed / chain32 / chain32_group",
                        " / ".join(mock) + " ns", conditions))
    raw = [f"{ns[f'loop/{r}/raw_{engine.lower()}/iterations:1'] / steps[r]:,.0f}"
           for r in ("seed", "chain32") if f"loop/{r}/raw_{engine.lower()}/iterations:1" in ns]
    if raw:
        rows.append(row(f"Raw {engine} per 1 ms step: seed / chain32", " / ".join(raw) + " ns", conditions))
    return rows


def loop_bullet(ctx):
    return _loop(ctx, "servoloop_bench_loop_vs_bullet", "Bullet", "loop_vs_bullet.txt")


def loop_mujoco(ctx):
    return _loop(ctx, "servoloop_bench_loop_vs_mujoco", "MuJoCo", "loop_vs_mujoco.txt")


# --- the node as users run it ------------------------------------------------------------------

SEED_LAUNCH = "robots/one_dof/one_dof_w_jnt_ctl.launch.yaml"
SEED_COMMAND = "/one_DOF_robot/joint1_position_controller/command:=1.0"


def instructions(ctx):
    """Instructions per step of the node and of the raw program (callgrind: deterministic)."""
    valgrind = shutil.which("valgrind")
    if valgrind is None:
        raise Skipped("valgrind is not installed")
    servoloop, raw = ctx.exe("servoloop"), ctx.exe("servoloop_bench_loop_vs_bullet")
    steps = 2000 if ctx.quick else 20000
    totals = {}
    for name, make in (("node", lambda n: [servoloop, "launch", SEED_LAUNCH, "--duration", f"{n / 1000:g}",
                                           "--rtf", "0", "--pub", SEED_COMMAND]),
                       ("raw", lambda n: [raw, "--raw-process", str(n)])):
        for n in (1, steps + 1):
            out = os.path.join(ctx.results, f"callgrind.{name}.{n}.out")
            subprocess.run([valgrind, "--tool=callgrind", f"--callgrind-out-file={out}"] + make(n), cwd=ctx.root,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            with open(out) as f:
                totals[(name, n)] = next(int(line.split()[1]) for line in f if line.startswith("summary:"))
    per_step = {name: (totals[(name, steps + 1)] - totals[(name, 1)]) / steps for name in ("node", "raw")}
    where = _extra_instructions_by_module(ctx, steps)
    start = {name: totals[(name, 1)] for name in ("node", "raw")}
    whole = {name: start[name] + 300000 * per_step[name] for name in ("node", "raw")}
    return [row(
        "Instructions: the node ÷ the raw program per step, and for a whole 300 s run (start-up included)",
        f"per step {per_step['node']:,.0f} ÷ {per_step['raw']:,.0f} = {per_step['node'] / per_step['raw']:.3f}; "
        f"start-up {start['node'] / 1e6:.1f} M ÷ {start['raw'] / 1e6:.1f} M; whole run "
        f"{whole['node'] / whole['raw']:.3f}",
        f"`valgrind --tool=callgrind`, runs of 1 and {steps + 1} steps of the two programs above (the difference "
        "is the per-step count); deterministic, unlike time on a shared VM"),
        row("Where the node's extra instructions per step go: the node's count minus the raw program's, by "
            "servoloop module (`bench`: the raw program's own control law) or library (`c`: the C library)", where,
            "the same callgrind runs, `callgrind_annotate` self counts per function, grouped by module")]


def _self_counts(path):
    """Self instruction counts per (function, object) of a callgrind output."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=no", "--threshold=100", path], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, text=True, check=True).stdout
    counts = {}
    for match in re.finditer(r"^\s*([\d,]+) \([^)]*\)\s+(.*)$", text, re.M):
        name = match.group(2).strip()
        if "PROGRAM TOTALS" not in name:
            counts[name] = counts.get(name, 0) + int(match.group(1).replace(",", ""))
    return counts


def _extra_instructions_by_module(ctx, steps):
    """The node's per-step self counts minus the raw program's, by servoloop module (the namespace) or library."""
    per_step = {}  # program -> function -> [instructions per step, group]
    for name in ("node", "raw"):
        one = _self_counts(os.path.join(ctx.results, f"callgrind.{name}.1.out"))
        many = _self_counts(os.path.join(ctx.results, f"callgrind.{name}.{steps + 1}.out"))
        per_step[name] = {}
        for key in set(one) | set(many):
            # "source:function [object]". The raw program links the simulation's code
            # into itself: a function is matched by its name, whichever object holds it.
            function, _, library = re.match(r"[^:]*:(.*?)(\s*\[([^\]]+)\])?$", key).group(1, 2, 3)
            module = re.match(r"(?:void |bool |[\w:<>]+ )?servoloop::(\w+)::", function)
            library = re.sub(r"\.so[.0-9]*$", "", os.path.basename(library or "?")).removeprefix("lib")
            entry = per_step[name].setdefault(function, [0.0, module.group(1) if module else library])
            entry[0] += (many.get(key, 0) - one.get(key, 0)) / steps
    by_group = {}
    for function in set(per_step["node"]) | set(per_step["raw"]):
        node_count, group = per_step["node"].get(function, [0.0, None])
        raw_count, raw_group = per_step["raw"].get(function, [0.0, None])
        group = group or raw_group
        by_group[group] = by_group.get(group, 0.0) + node_count - raw_count
    shown = sorted(((v, k) for k, v in by_group.items() if abs(v) >= 5), reverse=True)
    return "; ".join(f"{k} {v:+,.0f}" for v, k in shown)


def node(ctx):
    """bench_node.sh: 1. against cyclictest, 2. wall time per step against raw Bullet, 3. whole processes
    against the raw program."""
    env = {"BUILD_DIR": os.path.dirname(ctx.bin), "PARTS": "1 2 3", "ROUNDS": "2" if ctx.quick else "5",
           "PAIRS": "5" if ctx.quick else "21"}
    if ctx.quick:
        env.update({"SECONDS_PER_RUN": "2", "SIM_SECONDS": "10"})
    text = ctx.run(["bash", os.path.join(ctx.root, "scripts", "bench_node.sh")], "bench_node.txt", env=env)
    rows = []
    match = re.search(r"median: cyclictest p50 ([0-9.]+) p99 ([0-9.]+) max ([0-9.]+) us; servoloop p50 ([0-9.]+) "
                      r"p99 ([0-9.]+) max ([0-9.]+) us", text)
    ratio = re.search(r"servoloop p99 / cyclictest p99: median ([0-9.]+)", text)
    if match and ratio:
        rows.append(row("Wake-up latency at 1 kHz on the wall clock (the seed on the mock), servoloop ÷ "
                        "cyclictest: p99",
                        f"{float(ratio.group(1)):.2f}; cyclictest p50 / p99 / max {match.group(1)} / "
                        f"{match.group(2)} / {match.group(3)} us, servoloop {match.group(4)} / {match.group(5)} / "
                        f"{match.group(6)} us",
                        f"`scripts/bench_node.sh` part 1: {env['ROUNDS']} alternating rounds, "
                        "`cyclictest -q -m --default-system -t 1 -i 1000 -p 0`, normal scheduler, medians of the "
                        "rounds", "≤ 1.2: " + verdict(float(ratio.group(1)) <= 1.2)))
    else:
        rows.append(row("Wake-up latency against cyclictest", "not measured: no cyclictest (apt install rt-tests)",
                        "`scripts/bench_node.sh` part 1"))
    whole = re.search(r"raw program ([0-9]+) ms, node ([0-9]+) ms \(medians of (\d+); (\d+) steps\)\n\s*node / raw, "
                      r"wall: median ([0-9.]+) \(pairs ([0-9.]+)-([0-9.]+)\); CPU: median ([0-9.]+)", text)
    if whole is None:
        raise RuntimeError("bench_node.sh printed no whole-process figure; see bench_node.txt")
    ratio = float(whole.group(5))
    rows.insert(0, row(
        "Whole processes: `servoloop launch` of the seed (free-running) ÷ the raw program (loads the seed, builds "
        "its Bullet world with its collision shapes, steps it under the position law written out), start to exit",
        f"wall {ratio:.3f} (pairs {whole.group(6)}–{whole.group(7)}), CPU {whole.group(8)}; raw {whole.group(1)} ms, "
        f"node {whole.group(2)} ms",
        f"`scripts/bench_node.sh` part 3: {whole.group(4)} steps of 1 ms; {whole.group(3)} pairs in alternating "
        "order, medians", "≤ 1.05: " + verdict(ratio <= 1.05)))
    node = re.search(r"node / raw bullet: median ([0-9.]+) \(rounds: ([^)]*)\)", text)
    loop = re.search(r"loop thread / raw bullet: median ([0-9.]+)", text)
    if node:
        rows.append(row("Node ÷ raw Bullet, seed free-running, wall time per step (the node's summary; raw: "
                        "`loop/seed/raw_bullet`)",
                        f"{float(node.group(1)):.3f} (rounds {node.group(2)}); the loop thread alone "
                        f"{float(loop.group(1)):.3f}" if loop else node.group(1),
                        f"`scripts/bench_node.sh` part 2, {env['ROUNDS']} alternating rounds, each the median of 5 "
                        "node runs"))
    return rows


def startup(ctx):
    servoloop = ctx.exe("servoloop")
    runs = 5 if ctx.quick else 15
    version = [wall_and_cpu([servoloop, "--version"], ctx.root) for _ in range(runs)]
    launch = [wall_and_cpu([servoloop, "launch", SEED_LAUNCH, "--duration", "0.001", "--rtf", "0"], ctx.root)
              for _ in range(runs)]
    return [row("Start-up of a `servoloop` process: `servoloop --version` / a one-step `servoloop launch` of the "
                "seed, wall (CPU)",
                f"{median(w for w, _ in version) * 1e3:.0f} ms ({median(c for _, c in version) * 1e3:.0f} ms) / "
                f"{median(w for w, _ in launch) * 1e3:.0f} ms ({median(c for _, c in launch) * 1e3:.0f} ms)",
                f"medians of {runs} runs each")]


def seed_rtf(ctx):
    duration = 3 if ctx.quick else 30
    rows = []
    text = ctx.run([ctx.exe("servoloop_bench_seed_rtf"), "--duration", str(duration), "--repetitions", "5"],
                   "seed_rtf_in_process.txt")
    match = re.search(r"real-time factor: median ([0-9.]+) \(min ([0-9.]+), max ([0-9.]+)\)", text)
    if match:
        rows.append(row("Headless real-time factor of the seed run in process (`servoloop_bench_seed_rtf`)",
                        f"{float(match.group(1)):.0f} (runs {float(match.group(2)):.0f}–{float(match.group(3)):.0f})",
                        f"{duration} s simulated, 5 runs"))
    servoloop = ctx.exe("servoloop")
    loop, whole = [], []
    for run in range(3):
        start = time.perf_counter()
        out = subprocess.run([servoloop, "launch", SEED_LAUNCH, "--duration", str(duration), "--json"],
                             cwd=ctx.root, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=True)
        whole.append(duration / (time.perf_counter() - start))
        loop.append(json.loads(out.stdout)["real_time_factor"])
    rows.append(row(f"Headless real-time factor of `servoloop launch {SEED_LAUNCH} --duration {duration} --json`",
                    f"{median(loop):.0f} (runs {min(loop):.0f}–{max(loop):.0f}); {median(whole):.0f} including "
                    "start-up", "3 runs"))
    return rows


def spawner(ctx):
    servoloop = ctx.exe("servoloop")
    runs = 10 if ctx.quick else 30
    run_dir = tempfile.mkdtemp(prefix="servoloop-bench-run.")
    os.chmod(run_dir, 0o700)
    env = dict(os.environ, SERVOLOOP_RUN_DIR=run_dir)
    node = subprocess.Popen([servoloop, "launch", "bench/launch/one_dof_idle.launch.yaml"], cwd=ctx.root, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        socket_path = os.path.join(run_dir, "one_DOF_robot.sock")
        deadline = time.monotonic() + 30
        while not os.path.exists(socket_path):
            if time.monotonic() > deadline or node.poll() is not None:
                raise RuntimeError("the spawner benchmark's node did not open its socket")
            time.sleep(0.05)
        controllers = ["joint_state_controller", "joint1_position_controller"]
        ns = ["-N", "/one_DOF_robot"]

        def timed(args):
            start = time.perf_counter()
            subprocess.run([servoloop] + args, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                           check=True)
            return (time.perf_counter() - start) * 1e3

        spawns, lists = [], []
        for _ in range(runs):
            spawns.append(timed(["spawner"] + ns + controllers))
            lists.append(timed(["control", "list"] + ns))
            timed(["control", "stop"] + ns + controllers)
            timed(["control", "unload"] + ns + controllers)
    finally:
        node.send_signal(2)
        node.wait(timeout=30)
        shutil.rmtree(run_dir, ignore_errors=True)
    value = median(spawns)
    return [row("Spawner round trip (process start, connect, load 2 + start 2 in one switch, exit); "
                "`servoloop control list` for reference",
                f"{value:.1f} ms ({min(spawns):.1f}–{max(spawns):.1f}); control list {median(lists):.1f} ms",
                f"{runs} runs against a node running `bench/launch/one_dof_idle.launch.yaml`",
                "< 50 ms: " + verdict(value < 50))]


# --- one world, sensors, the view, episodes -------------------------------------------------------

def world(ctx):
    exe = ctx.exe("servoloop_bench_world")
    has_mujoco = os.path.exists(os.path.join(os.path.dirname(ctx.bin), "lib", "servoloop", "plugins",
                                             "libservoloop_sim_mujoco.so"))
    text = ctx.run([exe] + (["mujoco"] if has_mujoco else []), "world.txt")
    rows = []
    conditions = ("`servoloop_bench_world`: 16 boxes beside N seed arms, 1 ms steps; the raw engine (the "
                  "controllers' law written out), the shared node and the separate-worlds node built side by side "
                  "and stepped in turns of 250 steps; median of 3 rounds of 5,000 steps [lowest–highest]")
    for engine in ("bullet", "mujoco"):
        lines = re.findall(rf"^{engine}\s+(\d+)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9.]+) \[([0-9.]+)-([0-9.]+)\]\s+"
                           rf"([0-9.]+) \[[^]]*\]\s+([0-9.]+) \[([0-9.]+)-([0-9.]+)\]", text, re.M)
        if not lines:
            continue
        shared = " / ".join(f"{l[3]} [{l[4]}–{l[5]}]" for l in lines)
        separate = " / ".join(l[7] for l in lines)
        arms = " / ".join(l[0] for l in lines)
        worst = max(float(l[3]) for l in lines)
        rows.append(row(f"The shared world ÷ raw {engine}, {arms} arms, wall time", shared, conditions,
                        "≤ 1.10: " + verdict(worst <= 1.10)))
        rows.append(row(f"Separate worlds (`world: {{shared: false}}`) ÷ the shared world, {engine}, {arms} arms",
                        separate, conditions))
    return rows


def world_processes(ctx):
    exe, servoloop = ctx.exe("servoloop_bench_world"), ctx.exe("servoloop")
    pairs = 3 if ctx.quick else 9
    rows = []
    with tempfile.TemporaryDirectory(prefix="servoloop-bench-world.") as folder:
        for arms in (1, 16):
            directory = os.path.join(folder, f"arms{arms}")
            os.makedirs(directory)
            ctx.run([exe, "--write", directory, str(arms), "bullet"], f"world_write_{arms}.txt")
            node = [servoloop, "launch", os.path.join(directory, "world.launch.yaml"), "--duration", "5"]
            raw = [exe, "--raw", str(arms), "bullet"]
            wall, cpu, _, _ = paired(node, raw, pairs, ctx.root)
            rows.append(row(f"Whole processes, the shared world on bullet with {arms} arm(s) and 16 boxes: "
                            "`servoloop launch … --duration 5` ÷ the raw program of the same world",
                            f"wall {median(wall):.3f} (pairs {min(wall):.3f}–{max(wall):.3f}), CPU {median(cpu):.3f}",
                            f"launch file written by `servoloop_bench_world --write DIR {arms} bullet`, raw "
                            f"`servoloop_bench_world --raw {arms} bullet`; {pairs} pairs in alternating order",
                            "≤ 1.10: " + verdict(median(wall) <= 1.10)))
    return rows


def sensors(ctx):
    text = ctx.run([ctx.exe("servoloop_bench_sensors"), "mujoco"], "sensors.txt")
    rows = []
    header = re.search(r"=== Sensors: (.*) ===", text)
    for engine in ("bullet", "mujoco"):
        found = re.findall(rf"^{engine}\s+(\S+)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9.]+)\s+(-?[0-9.]+) ns", text, re.M)
        if found:
            rows.append(row(f"Sensors on {engine}: cost per sensor per control cycle, 8 sensors of one kind "
                            f"({', '.join(k for k, *_ in found)})",
                            " / ".join(f"{float(ns):.0f}" for *_, ns in found) + " ns; with ÷ without: " +
                            " / ".join(r for _, _, _, r, _ in found),
                            f"`servoloop_bench_sensors mujoco`: {header.group(1) if header else ''}"))
    return rows


def view(ctx):
    text = ctx.run([ctx.exe("servoloop_bench_view")], "view.txt")
    runs = re.findall(r"^(node alone|view, \d+ pages?)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9.]+)$", text, re.M)
    frames = re.findall(r"^\s*(\d+) page\(s\): ([0-9.]+) frames per second each", text, re.M)
    header = re.search(r"=== The view's cost: (.*) ===", text)
    value = "; ".join(f"{name.strip()}: {raw_ratio}" for name, _, raw_ratio, _ in runs)
    if frames:
        value += "; frames per second per page: " + ", ".join(f"{n} page(s) {f}" for n, f in frames)
    return [row("The browser view's cost: the node ÷ raw Bullet, alone and serving pages", value,
                f"`servoloop_bench_view`: {header.group(1) if header else ''}",
                "≥ 30 frames/s per page: " + verdict(bool(frames) and min(float(f) for _, f in frames) >= 30))]


def episodes(ctx):
    python = "/usr/bin/python3"
    python_dir = os.path.join(os.path.dirname(ctx.bin), "python")
    if not os.path.isdir(python_dir):
        raise Skipped("the Python package is not built")
    out = os.path.join(ctx.results, "episodes.json")
    ctx.run([python, os.path.join(ctx.root, "bench", "episodes", "bench_episodes.py"), "--json", out] +
            (["--episodes", "100"] if ctx.quick else []), "episodes.txt",
            env={"PYTHONPATH": python_dir, "SERVOLOOP": ctx.exe("servoloop")})
    with open(out) as f:
        figures = json.load(f)
    episodes = 100 if ctx.quick else 1000
    conditions = (f"`bench/episodes/bench_episodes.py`: {episodes} episodes of 5 s (seed, bullet, 1 kHz), wall "
                  "time; the Dask cluster (scheduler and 2 workers) on loopback on the same machine")
    rows = [row("Episodes per second: one World back to back / `servoloop sweep --jobs 1` / `--jobs 2` / a 2-worker "
                "Dask cluster",
                f"{figures['one_world_rate']:.1f} / {figures['sweep_jobs1_rate']:.1f} / "
                f"{figures['sweep_jobs2_rate']:.1f} / {figures['dask2_rate']:.1f}; --jobs 2 ÷ ideal scaling "
                f"{figures['sweep_jobs2_rate'] / (2 * figures['sweep_jobs1_rate']):.2f}, Dask ÷ --jobs 2 "
                f"{figures['dask2_rate'] / figures['sweep_jobs2_rate']:.2f}", conditions)]
    rows.append(row("`World.reset()` / a new World / a new `servoloop launch` process of one step; memory per World",
                    f"{figures['reset_s'] * 1e3:.2f} / {figures['new_world_s'] * 1e3:.1f} / "
                    f"{figures['new_process_s'] * 1e3:.1f} ms; {figures['memory_per_world_mib']:.2f} MiB",
                    conditions))
    cluster = 100 * figures["dask2_rate"]
    rows.append(row("A cluster of 100 such 2-vCPU machines, estimated: episodes per second (per hour)",
                    f"{cluster:,.0f} ({cluster * 3600 / 1e6:.0f} million an hour)",
                    "an estimate, not a measurement: 100 × this run's 2-worker rate (one `dask-worker` with 2 threads "
                    "per machine; the scheduler and client, here on the same 2 vCPUs, elsewhere)"))
    return rows


def plugin_compile(ctx):
    build_dir = os.path.dirname(ctx.bin)
    rows = []
    text = ctx.run(["bash", os.path.join(ctx.root, "scripts", "check_plugin_build_time.sh"), build_dir, "3", "1000"],
                   "plugin_rebuild.txt")
    rebuild = re.search(r"median ([0-9.]+) s of (\d+)", text)
    if rebuild:
        value = float(rebuild.group(1))
        rows.append(row("A plugin author's rebuild: `examples/custom_controller` against the installed package, "
                        "source touched, `ninja` (recompile and relink)", f"{value:.2f} s",
                        f"`scripts/check_plugin_build_time.sh`, RelWithDebInfo, median of {rebuild.group(2)}",
                        "< 3 s (CI fails above 5 s): " + verdict(value < 3)))
    runs = 1 if ctx.quick else 3
    text = ctx.run(["bash", os.path.join(ctx.root, "scripts", "measure_plugin_compile.sh"), build_dir, str(runs)],
                   "plugin_compile.txt")
    builds = [float(x) for x in re.findall(r"^build \d+: ([0-9.]+) s", text, re.M)]
    lines = re.search(r"preprocessed: (\d+) lines", text)
    if builds:
        rows.append(row("Out-of-tree build of a 50-line controller against the installed package, from clean, "
                        "without precompiled headers; its preprocessed size",
                        f"{median(builds):.1f} s (builds {', '.join(f'{b:.1f}' for b in builds)}); "
                        f"{int(lines.group(1)):,} lines" if lines else f"{median(builds):.1f} s",
                        f"`scripts/measure_plugin_compile.sh`, {runs} builds, no build type"))
    return rows


def first_build(ctx):
    """The README's two commands on a fresh clone: what a newcomer waits for."""
    with tempfile.TemporaryDirectory(prefix="servoloop-fresh.") as folder:
        clone = os.path.join(folder, "servoloop")
        subprocess.run(["git", "clone", "--quiet", "--no-hardlinks", ctx.root, clone], check=True)
        head = subprocess.run(["git", "-C", clone, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                              text=True, check=True).stdout.strip()
        timings = {}
        for name, script in (("main job", "main_job.sh"), ("test command", "test.sh")):
            start = time.perf_counter()
            text = ctx.run(["bash", os.path.join("scripts", script)], f"fresh_{script}.txt", cwd=clone,
                           timeout=7200)
            timings[name] = (time.perf_counter() - start, text)
    tests = re.search(r"(\d+)% tests passed, (\d+) tests failed out of (\d+)", timings["test command"][1])
    test_time = re.search(r"Total Test time \(real\) = +([0-9.]+) sec", timings["test command"][1])

    def minutes(seconds):
        return f"{int(seconds // 60)} min {int(seconds % 60)} s"

    main_s = timings["main job"][0]
    rows = [row("First build and run of the main job, `bash scripts/main_job.sh` from a fresh clone (build what "
                "the seed run needs, run it, plot)", minutes(main_s),
                f"a fresh clone of {head}, empty `build/`, dependencies installed", "< 5 min: " + verdict(main_s < 300))]
    test_s = timings["test command"][0]
    rows.append(row("The test command after it, `bash scripts/test.sh` (the rest of the build and every test suite)",
                    f"{minutes(test_s)}" + (f", of which {minutes(float(test_time.group(1)))} run the tests" if test_time
                                            else "") +
                    (f"; {int(tests.group(3)) - int(tests.group(2))} of {tests.group(3)} passed" if tests else ""),
                    "as above, after the main job"))
    return rows


def ros1_bridge(ctx):
    exe = os.path.join(ctx.bin, "servoloop_bench_ros1_bridge")
    if not os.access(exe, os.X_OK) or shutil.which("roscore") is None:
        raise Skipped("the ROS 1 bridge is not built or ROS 1 is not installed (scripts/install_ros1.sh)")
    text = ctx.run(["bash", os.path.join(ctx.root, "scripts", "bench_ros1.sh")], "ros1.txt",
                   env={"BUILD_DIR": os.path.dirname(ctx.bin)})
    latency = dict(re.findall(r"^(ipc|ros) command latency: (\d+ of \d+ arrived; p50 [0-9.]+ ms, p99 [0-9.]+ ms)",
                              text, re.M))
    loops = re.findall(r"^loop: cycles \d+, overruns (\d+); compute p50 ([0-9.]+) us, p99 ([0-9.]+) us", text, re.M)
    rates = re.findall(r"^delivery of \S+ at (\d+) Hz: .*\(([0-9.]+) per wall second\); missing (\d+), repeated (\d+)",
                       text, re.M)
    if set(latency) != {"ipc", "ros"} or len(loops) < 2:
        raise RuntimeError("bench_ros1.sh printed no command latency or loop figures; see ros1.txt")
    conditions = ("`scripts/bench_ros1.sh`: its own roscore, the seed robot (`--rtf 1`, Bullet, 1 kHz); two 10 s "
                  "windows with the same client work (commands in at 100 Hz, joint states out at 50 Hz), over the "
                  "node's socket and through the bridge; a command is timed from its publication to its arrival in "
                  "the node")
    rows = [row("ROS 1 command latency, roscpp publisher → bridge → node (over the node's socket for reference)",
                f"{latency['ros']} (socket: {latency['ipc']})", conditions)]
    rows.append(row("The node's loop during each window: compute p50 / p99, overruns; socket → bridge",
                    f"{loops[0][1]} / {loops[0][2]} us, {loops[0][0]} → {loops[1][1]} / {loops[1][2]} us, "
                    f"{loops[1][0]}", conditions))
    if rates:
        rows.append(row("Joint states to a roscpp subscriber, per wall second",
                        "; ".join(f"{rate} at {hz} Hz (missing {missing}, repeated {repeated})"
                                  for hz, rate, missing, repeated in rates), conditions))
    return rows
