#!/usr/bin/python3
"""The benchmarks' guard: quick runs of benchmarks 1 and 2, each figure a ratio
to a baseline measured in the same run (so the machine's speed cancels), checked
against the figures recorded in bench/guard/recorded.json.

A figure fails when it is more than FACTOR (1.5) times its recorded value in
two runs: a figure over its bound is measured again and the lower value counts
(a burst of load on a shared machine slows one run, a regression both).
--record writes the median of three runs as the new record (with the date, the
commit and the machine), after a change that moves a figure on purpose.

Usage: bench_guard.py BIN_DIR [--record] [--factor 1.5] [--repetitions 9]
"""
import argparse
import datetime
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
RECORDED = os.path.join(HERE, "recorded.json")

MANAGER = "servoloop_bench_controller_manager"
LOOP = "servoloop_bench_loop_vs_bullet"
MANAGER_VARIANTS = {
    "empty": "manager/empty/joints:1",
    "one_joint": "manager/per_joint/jsc_50Hz/joints:1",
    "sixty_four_joints": "manager/per_joint/jsc_50Hz/joints:64",
    "one_joint_timed": "manager/per_joint_timed/jsc_50Hz/joints:1",
    "sixty_four_joints_timed": "manager/per_joint_timed/jsc_50Hz/joints:64",
}

# name: (what it is, numerator, denominator); the numerator and denominator
# name manager variants above, or a paired ratio of benchmark 2.
FIGURES = {
    "manager_1_joint_per_empty": (
        "manager, 1 JointPositionController + JointStateController (50 Hz) / empty manager",
        "one_joint", "empty"),
    "manager_64_joints_per_empty": (
        "manager, 64 JointPositionControllers + JointStateController (50 Hz) / empty manager",
        "sixty_four_joints", "empty"),
    "manager_timed_per_untimed_1_joint": (
        "manager with update timing as the node's loops sample it / untimed, 1 joint",
        "one_joint_timed", "one_joint"),
    "manager_timed_per_untimed_64_joints": (
        "manager with update timing as the node's loops sample it / untimed, 64 joints",
        "sixty_four_joints_timed", "sixty_four_joints"),
    "loop_seed_per_raw_bullet": (
        "whole loop on bullet / raw Bullet stepping with an inline PID, seed robot (paired episodes)",
        "paired:seed", None),
    "loop_chain32_per_raw_bullet": (
        "whole loop on bullet / raw Bullet, chain32 (32 JointPositionControllers, paired episodes)",
        "paired:chain32", None),
}


def run(command):
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        sys.stdout.write(result.stdout)
        sys.exit(f"bench_guard: {' '.join(command)} exited with {result.returncode}")
    return result.stdout


def manager_medians(bin_dir, repetitions):
    """Thread CPU ns per cycle, median over interleaved repetitions, of each manager variant."""
    names = "|".join(re.escape(name) for name in MANAGER_VARIANTS.values())
    with tempfile.TemporaryDirectory(prefix="servoloop-bench-guard.") as folder:
        out = os.path.join(folder, "manager.json")
        run([os.path.join(bin_dir, MANAGER), f"--benchmark_filter=^({names})$",
             f"--benchmark_repetitions={repetitions}", "--benchmark_min_time=0.05",
             "--benchmark_enable_random_interleaving=true",
             f"--benchmark_out={out}", "--benchmark_out_format=json"])
        with open(out) as f:
            report = json.load(f)
    times = {}
    for entry in report["benchmarks"]:
        if entry.get("run_type") != "iteration":
            continue
        times.setdefault(entry["run_name"], []).append(entry["cpu_time"])
    medians = {}
    for key, name in MANAGER_VARIANTS.items():
        if name not in times:
            sys.exit(f"bench_guard: {MANAGER} ran no benchmark named {name}")
        medians[key] = statistics.median(times[name])
    return medians


def paired_ratios(bin_dir, repetitions):
    """Median servoloop / raw Bullet thread CPU ratio of back-to-back episodes, per robot."""
    text = run([os.path.join(bin_dir, LOOP), "--benchmark_filter=^loop/(seed|chain32)/paired/",
                f"--benchmark_repetitions={repetitions}"])
    ratios = {}
    for match in re.finditer(r"^\s+(\S+): paired\s+([0-9.]+) median of (\d+) pairs", text, re.M):
        ratios[match.group(1)] = float(match.group(2))
    for robot in ("seed", "chain32"):
        if robot not in ratios:
            sys.stdout.write(text)
            sys.exit(f"bench_guard: {LOOP} printed no paired ratio for {robot}")
    return ratios


def measure(bin_dir, repetitions):
    medians = manager_medians(bin_dir, repetitions)
    paired = paired_ratios(bin_dir, repetitions)
    figures = {}
    for name, (_, numerator, denominator) in FIGURES.items():
        if numerator.startswith("paired:"):
            figures[name] = paired[numerator.split(":", 1)[1]]
        else:
            figures[name] = medians[numerator] / medians[denominator]
    return figures, medians


def commit():
    try:
        return subprocess.run(["git", "-C", HERE, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bin_dir", help="the build's bin/ folder (the benchmarks' executables)")
    parser.add_argument("--record", action="store_true", help="write the measured figures to recorded.json")
    parser.add_argument("--factor", type=float, default=1.5, help="fail above this many times the record")
    parser.add_argument("--repetitions", type=int, default=9)
    args = parser.parse_args()
    if not (args.factor > 1.0):
        sys.exit(f"bench_guard: --factor must be above 1, got {args.factor}")
    if args.repetitions < 3:
        sys.exit(f"bench_guard: --repetitions must be 3 or more (medians), got {args.repetitions}")

    def measure_and_print():
        figures, medians = measure(args.bin_dir, args.repetitions)
        print("bench_guard: manager variants, thread CPU ns per cycle (medians of "
              f"{args.repetitions} interleaved repetitions):")
        for key, name in MANAGER_VARIANTS.items():
            print(f"  {name:<46} {medians[key]:9.1f} ns")
        return figures

    figures = measure_and_print()
    if args.record:
        runs = [figures, measure_and_print(), measure_and_print()]
        figures = {name: statistics.median(run[name] for run in runs) for name in figures}
        record = {
            "recorded": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "commit": commit(),
            "machine": f"{os.cpu_count()} CPUs, {platform.processor() or platform.machine()}, "
                       f"Linux {platform.release()}",
            "figures": {name: round(value, 4) for name, value in figures.items()},
        }
        with open(RECORDED, "w") as f:
            json.dump(record, f, indent=2)
            f.write("\n")
        print(f"bench_guard: recorded {len(figures)} figures in {RECORDED}")
        for name, value in figures.items():
            print(f"  {name:<40} {value:7.3f}   {FIGURES[name][0]}")
        return 0

    with open(RECORDED) as f:
        record = json.load(f)
    for name in figures:
        if name not in record["figures"]:
            sys.exit(f"bench_guard: {RECORDED} has no figure '{name}'; record the figures with --record")
    over = [name for name, value in figures.items() if value > args.factor * record["figures"][name]]
    if over:
        print(f"bench_guard: {', '.join(over)} over the bound; measuring again")
        again = measure_and_print()
        figures = {name: min(value, again[name]) if name in over else value for name, value in figures.items()}
    failed = []
    print(f"bench_guard: figures against the record of {record['recorded']} ({record['commit']}), "
          f"failing above {args.factor} x:")
    for name, value in figures.items():
        recorded = record["figures"][name]
        ratio = value / recorded
        verdict = "ok" if ratio <= args.factor else "FAILED"
        print(f"  {name:<40} {value:7.3f}  recorded {recorded:7.3f}  ({ratio:5.2f} x)  {verdict}   "
              f"{FIGURES[name][0]}")
        if ratio > args.factor:
            failed.append(name)
    if failed:
        print(f"bench_guard: FAILED: {', '.join(failed)} more than {args.factor} x the recorded figure")
        return 1
    print("bench_guard: every figure within its bound")
    return 0


if __name__ == "__main__":
    sys.exit(main())
