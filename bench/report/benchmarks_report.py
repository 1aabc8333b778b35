#!/usr/bin/python3
"""Runs servoloop's benchmarks and writes docs/benchmarks.md from their figures.

    bench/report/benchmarks_report.py --bin BUILD/bin [--results DIR] [--quick]
        [--only SECTION[,SECTION]] [--write docs/benchmarks.md]
    bench/report/benchmarks_report.py --render DIR/figures.json --write docs/benchmarks.md

Every figure is stamped with the time and the commit it was measured at and
the conditions it was measured under; the page shows these figures only (the
prose around them is bench/report/benchmarks.md.in). --only re-measures some
sections and keeps the others' figures from the previous figures.json in
--results. scripts/run_benchmarks.sh builds and calls this.
"""
import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import traceback

import runners

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
TEMPLATE = os.path.join(HERE, "benchmarks.md.in")

# (key, title, runners): the page's tables, in order.
SECTIONS = [
    ("cycle", "The control cycle", [runners.manager]),
    ("loop", "The loop in process against the raw engine", [runners.loop_bullet, runners.loop_mujoco]),
    ("node", "The node as users run it",
     [runners.node, runners.instructions, runners.startup,
      runners.seed_rtf, runners.spawner]),
    ("world", "One world", [runners.world, runners.world_processes]),
    ("sensors", "Sensors and the browser view", [runners.sensors, runners.view]),
    ("episodes", "Episodes", [runners.episodes]),
    ("authors", "Plugin authors and ROS 1", [runners.plugin_compile, runners.ros1_bridge]),
    ("build", "A newcomer's first build", [runners.first_build]),
]


def git(*args):
    try:
        return subprocess.run(["git", "-C", ROOT] + list(args), stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def commit():
    """The commit measured: HEAD, and whether tracked files other than this page differ from it."""
    head = git("rev-parse", "--short", "HEAD") or "unknown"
    dirty = git("status", "--porcelain", "--untracked-files=no", "--", ".", ":!docs/benchmarks.md")
    return f"{head} + working tree" if dirty else head


def cmake_cache(build_dir, key):
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt")) as cache:
            for line in cache:
                if line.startswith(key + ":"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return "?"


def machine(build_dir):
    cpu = "?"
    with open("/proc/cpuinfo") as info:
        for line in info:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    with open("/proc/meminfo") as info:
        memory_gib = int(info.readline().split()[1]) / 2**20
    compiler = subprocess.run([cmake_cache(build_dir, "CMAKE_CXX_COMPILER"), "-dumpfullversion"],
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.strip() \
        if cmake_cache(build_dir, "CMAKE_CXX_COMPILER") != "?" else "?"
    return (f"{os.cpu_count()} CPUs, {cpu}, {memory_gib:.0f} GiB, Linux {platform.release()}; build type "
            f"{cmake_cache(build_dir, 'CMAKE_BUILD_TYPE') or 'default'}, compiler {os.path.basename(cmake_cache(build_dir, 'CMAKE_CXX_COMPILER'))} {compiler}; "
            f"load average {os.getloadavg()[0]:.1f} at the start")


def now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")


def measure(args, previous):
    context = runners.Context(ROOT, os.path.abspath(args.bin), args.results, args.quick)
    only = set(args.only.split(",")) if args.only else None
    sections, failures = {}, []
    # Taken once: the benchmarks and scripts run are those of the start.
    stamp = commit()
    for key, _, functions in SECTIONS:
        if only is not None and key not in only:
            sections[key] = previous.get("sections", {}).get(key, [])
            continue
        rows = []
        for function in functions:
            started = now()
            print(f"== {key}: {function.__name__} ({started})", flush=True)
            try:
                measured = function(context)
            except runners.Skipped as skipped:
                measured = [runners.row(f"`{function.__name__}`", f"not measured: {skipped}", "—")]
            except Exception as error:  # one broken benchmark must not lose the others' figures
                traceback.print_exc()
                failures.append(function.__name__)
                measured = [runners.row(f"`{function.__name__}`", f"failed: {error}", "—")]
            for figure in measured:
                figure.update({"measured": started, "commit": stamp, "quick": args.quick})
                print(f"   {figure['figure']}: {figure['value']}", flush=True)
            rows += measured
        sections[key] = rows
    figures = {"machine": machine(os.path.dirname(os.path.abspath(args.bin))), "generated": now(),
               "sections": sections}
    return figures, failures


def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def render(figures):
    with open(TEMPLATE) as f:
        page = f.read()
    for key, title, _ in SECTIONS:
        rows = figures["sections"].get(key, [])
        lines = [f"### {title}", "", "| figure | value | target | conditions | measured |", "|---|---|---|---|---|"]
        previous = None
        for figure in rows:
            measured = f"{figure['measured']}, {figure['commit']}" + (" (quick run)" if figure.get("quick") else "")
            conditions = "as above" if figure["conditions"] == previous else figure["conditions"]
            previous = figure["conditions"]
            lines.append("| " + " | ".join(cell(v) for v in (figure["figure"], figure["value"], figure["target"],
                                                              conditions)) + f" | {cell(measured)} |")
        if not rows:
            lines.append("| (not measured) | | | | |")
        page = page.replace("{{figures:" + key + "}}", "\n".join(lines))
    page = page.replace("{{machine}}", figures["machine"]).replace("{{generated}}", figures["generated"])
    if "{{" in page:
        raise SystemExit(f"benchmarks_report: {TEMPLATE} has a placeholder this script does not fill")
    return page


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", help="the build's bin/ folder")
    parser.add_argument("--results", help="where the outputs and figures.json go (default: BIN/../benchmark-results/<UTC time>)")
    parser.add_argument("--quick", action="store_true", help="fewer repetitions and shorter runs")
    parser.add_argument("--only", help="comma-separated sections to measure: " + ", ".join(k for k, _, _ in SECTIONS))
    parser.add_argument("--render", help="a figures.json to render instead of measuring")
    parser.add_argument("--write", help="the page to write (e.g. docs/benchmarks.md)")
    args = parser.parse_args()
    if args.only and any(key not in {k for k, _, _ in SECTIONS} for key in args.only.split(",")):
        parser.error(f"--only takes sections among: {', '.join(k for k, _, _ in SECTIONS)}")
    failures = []
    if args.render:
        with open(args.render) as f:
            figures = json.load(f)
    else:
        if not args.bin:
            parser.error("--bin is needed to measure (or --render FIGURES_JSON)")
        if args.results is None:
            stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
            args.results = os.path.join(os.path.dirname(os.path.abspath(args.bin)), "benchmark-results", stamp)
        os.makedirs(args.results, exist_ok=True)
        previous = {}
        previous_path = os.path.join(args.results, "figures.json")
        if args.only and os.path.exists(previous_path):
            with open(previous_path) as f:
                previous = json.load(f)
        figures, failures = measure(args, previous)
        with open(previous_path, "w") as f:
            json.dump(figures, f, indent=1, ensure_ascii=False)
            f.write("\n")
        print(f"benchmarks_report: figures in {previous_path}")
    if args.write:
        page = render(figures)
        with open(args.write, "w") as f:
            f.write(page)
        print(f"benchmarks_report: wrote {args.write}")
    if failures:
        print(f"benchmarks_report: FAILED: {', '.join(failures)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
