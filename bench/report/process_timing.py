"""Whole processes timed from outside, start to exit: wall and CPU seconds,
and two commands in alternating pairs (bench_node.sh part 3 and the report's
world processes use the same pairing)."""
import resource
import subprocess
import time


def children_cpu():
    """User + system seconds of the finished children so far (getrusage, not
    os.times: the latter counts in clock ticks of 10 ms)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def wall_and_cpu(command, cwd):
    """Wall and CPU (user + system) seconds of one process, start to exit."""
    before, start = children_cpu(), time.perf_counter()
    subprocess.run(command, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    return time.perf_counter() - start, children_cpu() - before


def paired(a, b, pairs, cwd):
    """A and B in alternating order (A B, B A, ...) after one unmeasured run of
    each: the per-pair wall and CPU ratios A ÷ B, and A's and B's wall times."""
    wall_and_cpu(a, cwd), wall_and_cpu(b, cwd)  # both programs' files in the page cache
    wall, cpu, a_walls, b_walls = [], [], [], []
    for pair in range(pairs):
        if pair % 2 == 0:
            ta, tb = wall_and_cpu(a, cwd), wall_and_cpu(b, cwd)
        else:
            tb, ta = wall_and_cpu(b, cwd), wall_and_cpu(a, cwd)
        wall.append(ta[0] / tb[0])
        cpu.append(ta[1] / tb[1])
        a_walls.append(ta[0])
        b_walls.append(tb[0])
    return wall, cpu, a_walls, b_walls
