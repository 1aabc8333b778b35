"""Plots of a sweep's results with gnuplot: one PNG per measure and parameter.

`servoloop sweep` draws each measure against each varied or drawn parameter
(points, one per successful episode) so that a sweep's outcome can be seen
without further tools. gnuplot is run as a program on a script file and data
files in a temporary directory; user text (parameter paths, measure names,
file names) reaches the script only inside gnuplot's single-quoted strings.
"""
from __future__ import annotations

import math
import os
import shutil
import subprocess
import tempfile


def plot_file_name(measure: str, parameter: str) -> str:
    """final_q, /robot/pid/p -> final_q_vs_robot_pid_p.png"""
    return f"{measure}_vs_{parameter.strip('/').replace('/', '_')}.png"


def _quote(text: str) -> str:
    """A gnuplot single-quoted string: '' stands for a quote, nothing else is special."""
    return "'" + str(text).replace("'", "''") + "'"


def _number(text: str):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def _script(terminal: str, plots: list[dict]) -> str:
    lines = [f"set terminal {terminal} noenhanced size 800,600", "set key off", "set grid"]
    for plot in plots:
        lines += [
            f"set output {_quote(plot['output'])}",
            f"set title {_quote(plot['measure'] + ' vs ' + plot['parameter'])}",
            f"set xlabel {_quote(plot['parameter'])}",
            f"set ylabel {_quote(plot['measure'])}",
        ]
        if plot["categories"]:
            tics = ", ".join(f"{_quote(label)} {index}" for index, label in enumerate(plot["categories"]))
            lines += [f"set xtics ({tics})", f"set xrange [-0.5:{len(plot['categories']) - 0.5}]",
                      "set offsets 0, 0, graph 0.05, graph 0.05"]
        else:
            # Margins keep the points at the ends of the ranges off the frame.
            lines += ["set xtics autofreq", "set autoscale x",
                      "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05"]
        lines += [f"plot {_quote(plot['data'])} using 1:2 with points pointtype 7 pointsize 1.2", "unset output"]
    return "\n".join(lines) + "\n"


def plot_sweep(rows: list[dict], parameters: list[str], measures: list[str], directory: str) -> tuple[list[str], str]:
    """Plot every measure against every parameter from the CSV's rows (strings).
    Returns (the PNG files written, a note when some or all could not be made)."""
    gnuplot = shutil.which("gnuplot")
    if gnuplot is None:
        return [], "gnuplot is not installed (apt install gnuplot-nox); no plots"
    good = [row for row in rows if not row.get("error")]
    if not good:
        return [], "no episode succeeded; no plots"
    os.makedirs(directory, exist_ok=True)
    skipped = []
    with tempfile.TemporaryDirectory(prefix="servoloop-sweep-plot-") as scratch:
        plots = []
        for measure in measures:
            for parameter in parameters:
                points = [(row[parameter], _number(row[measure])) for row in good]
                points = [(x, y) for x, y in points if y is not None]
                if not points:
                    skipped.append(f"{measure} (not a number)")
                    break
                xs = [_number(x) for x, _ in points]
                categories = []
                if any(x is None for x in xs):
                    # Not numbers (e.g. joint names): one column of points per value.
                    categories = list(dict.fromkeys(x for x, _ in points))
                    xs = [categories.index(x) for x, _ in points]
                data = os.path.join(scratch, f"{len(plots)}.dat")
                with open(data, "w", encoding="utf-8") as stream:
                    stream.writelines(f"{x!r} {y!r}\n" for x, (_, y) in zip(xs, points))
                plots.append({"measure": measure, "parameter": parameter, "data": data, "categories": categories,
                              "output": os.path.join(directory, plot_file_name(measure, parameter))})
        if not plots:
            return [], "nothing to plot: " + ", ".join(skipped)
        script = os.path.join(scratch, "plots.gp")
        failure = ""
        for terminal in ("pngcairo", "png"):
            with open(script, "w", encoding="utf-8") as stream:
                stream.write(_script(terminal, plots))
            try:
                done = subprocess.run([gnuplot, script], capture_output=True, text=True, timeout=120)
            except (OSError, subprocess.TimeoutExpired) as e:
                return [], f"gnuplot failed ({e}); no plots"
            if done.returncode == 0:
                break
            failure = " ".join(done.stderr.split())[-300:]
        else:
            return [], f"gnuplot failed ({failure}); no plots"
    written = [plot["output"] for plot in plots if os.path.isfile(plot["output"])]
    note = f"not plotted: {', '.join(skipped)}" if skipped else ""
    return written, note
