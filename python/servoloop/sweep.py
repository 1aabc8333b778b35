"""`servoloop sweep`: run a launch file's world over a grid and/or random
samples of parameters and tabulate what each episode measured.

    python3 -m servoloop.sweep SPEC.yaml --out DIR [--jobs N]
                               [--scheduler tcp://HOST:PORT] [--resume]

(the `servoloop sweep` command runs exactly this). Tuning gains or checking a
controller's robustness takes many episodes of the same world with different
parameters; this runs them in parallel threads (each World releases the GIL
while it steps) or on a Dask cluster, and writes:

  DIR/episodes.csv  one row per episode: id, each parameter, repeat, each
                    measure, worker, wall_time_s, error (floats exact: repr)
  DIR/sweep.json    the spec's canonical content and the episode list, which
                    --resume checks so that a resumed sweep is the same sweep
  DIR/plots/        <measure>_vs_<parameter>.png for every pair (gnuplot)

The spec's format and its checks are in sweep_spec.py. An episode that fails
(its world cannot be built, a publication is rejected, a measured topic is
silent...) gets its error in the `error` column and empty measures; the sweep
goes on. Rows are appended as episodes finish, so an interrupted sweep keeps
them and `--resume` runs only the missing ones.

Exit status: 0 every episode succeeded; 1 the sweep ran but some episodes
failed (see their `error`); 2 bad arguments or spec, an unreachable Dask
scheduler, or Dask workers that cannot run episodes; 130 interrupted (Ctrl-C).
"""
from __future__ import annotations

import argparse
import concurrent.futures
import csv
import json
import logging
import os
import shlex
import sys
import threading
import time

from . import Error, World
from .sweep_plot import plot_sweep
from .sweep_spec import SpecError, check_against_world, episodes, extract, load_spec, parse_field, reduce_values

PROG = "servoloop sweep"
SCHEDULER_TIMEOUT_S = 10


class SweepError(Exception):
    """A problem that stops the sweep (exit status 2), with its message."""


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during a local run; `abandoned` when a second Ctrl-C left
    episodes running (the process then exits without waiting for them)."""

    def __init__(self, abandoned: bool):
        super().__init__()
        self.abandoned = abandoned


def _one_line(error: BaseException) -> str:
    text = " ".join(str(error).split())
    if isinstance(error, Error):
        return text or type(error).__name__
    return f"{type(error).__name__}: {text}" if text else type(error).__name__


def _worker_name() -> str:
    """The Dask worker's name (or address) on a Dask worker, else this thread's."""
    distributed = sys.modules.get("distributed")
    if distributed is not None:
        try:
            worker = distributed.get_worker()
        except ValueError:
            pass  # not on a worker: a local thread
        else:
            return str(worker.name if worker.name is not None else worker.address)
    name = threading.current_thread().name
    return name.replace("_", "-") if name.startswith("local_") else name


def _measure(world: World, task: dict) -> dict:
    """Run one episode in `world` and reduce each measure's messages."""
    topics = world.topics
    for name, entry in task["measure"].items():
        if entry["topic"] not in topics:
            raise Error(f"measure '{name}': topic {entry['topic']} is not in this episode's world "
                        "(did its controller fail to load? see the log)")
    for entry in task["publish"]:
        if entry["topic"] not in topics:
            raise Error(f"publish: topic {entry['topic']} is not in this episode's world "
                        "(did its controller fail to load? see the log)")
    wanted = sorted({entry["topic"] for entry in task["measure"].values()})
    for topic in wanted:
        world.subscribe(topic)  # the first call subscribes
    def step_to(time_s):
        if time_s > world.time:
            wanted = round((time_s - world.time) / world.time_step)
            ran = world.step(time_s - world.time)
            if ran < wanted:
                raise Error(f"the world ran {ran} of {wanted} steps to t = {time_s} s (a robot stopped: see the log)")

    for entry in sorted(task["publish"], key=lambda entry: entry["time"]):
        step_to(entry["time"])
        world.publish(entry["topic"], entry["value"], entry["type"])
    step_to(task["duration"])
    messages = {topic: world.subscribe(topic) for topic in wanted}
    results = {}
    for name, entry in task["measure"].items():
        received = messages[entry["topic"]]
        if not received:
            raise Error(f"measure '{name}': topic {entry['topic']} published no message in the episode")
        path = parse_field(entry["field"])
        values = [extract(message["msg"], path, message.get("type") or entry["topic"]) for message in received]
        results[name] = reduce_values(values, entry["reduce"])
    return results


class _WorldCache(threading.local):
    """Each thread's World, kept from one episode to the next when every
    parameter the sweep sets belongs to a controller (<ns>/<controller>/...,
    a namespace with a `type`): then an episode is set_param + reset(), which
    reloads the changed controllers and gives the run a fresh World gives
    (docs/simulation.md, "Pause, step and reset"), in a fraction of the time.
    Any other parameter (the simulation's, a robot's) needs a new World."""

    world = None
    source = None  # (launch, backend, the parameter names a sweep sets) of `world`
    controllers: set = frozenset()

    def drop(self):
        if self.world is not None:
            try:
                self.world.close()
            except Exception:  # noqa: BLE001 - a broken world is dropped anyway
                pass
        self.world, self.source, self.controllers = None, None, frozenset()


_cache = _WorldCache()


def _controller_namespaces(tree, prefix: str = "") -> set:
    found = set()
    if isinstance(tree, dict):
        if isinstance(tree.get("type"), str) and "/" in tree["type"]:
            found.add(prefix)
        for key, value in tree.items():
            found |= _controller_namespaces(value, f"{prefix}/{key}")
    return found


def _world_for(task: dict) -> World:
    """The world of an episode: this thread's, reset with the episode's
    parameters when it may be reused, else a new one (kept for the next)."""
    params = task["params"]
    # The same names every episode of one sweep: a World of another sweep
    # (another set of names) keeps values this one would not overwrite.
    source = (task["launch"], task["backend"], frozenset(params))
    reusable = _cache.world is not None and _cache.source == source and all(
        any(path.startswith(ns + "/") for ns in _cache.controllers) for path in params)
    if reusable:
        try:
            for path, value in params.items():
                _cache.world.set_param(path, value)
            _cache.world.reset()
            return _cache.world
        except Error:
            pass  # a controller that cannot be reloaded in place: a new World decides
    _cache.drop()
    world = World(task["launch"], backend=task["backend"], params=params, log_level="error")
    _cache.world, _cache.source = world, source
    _cache.controllers = _controller_namespaces(world.get_param("/"))
    return world


def run_episode(task: dict) -> dict:
    """One episode, self-contained so that a Dask worker can run it: the
    world with the episode's parameters (_world_for), publications at their
    times, steps to the duration, the measures reduced. Never raises: a
    failure is the row's `error` (and the world is not reused)."""
    start = time.perf_counter()
    row = {"id": task["id"], "params": task["params"], "repeat": task["repeat"], "measures": {}, "error": ""}
    try:
        row["measures"] = _measure(_world_for(task), task)
    except Exception as e:  # noqa: BLE001 - any failure belongs in the row, and the sweep goes on
        _cache.drop()
        row["measures"] = {}
        row["error"] = _one_line(e)
    row["worker"] = _worker_name()
    row["wall_time_s"] = time.perf_counter() - start
    return row


def run_batch(tasks: list[dict]) -> list[dict]:
    """Several episodes in one Dask task (fewer round trips to the scheduler)."""
    return [run_episode(task) for task in tasks]


def make_tasks(spec, episode_list: list[dict]) -> list[dict]:
    common = {"launch": spec.launch, "backend": spec.backend, "duration": spec.duration,
              "publish": spec.publish, "measure": spec.measure}
    return [{**common, **episode} for episode in episode_list]


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, (dict, list)):
        return json.dumps(value)
    return repr(value) if isinstance(value, float) else str(value)


class Results:
    """episodes.csv: rows appended and flushed as episodes finish, then the
    whole file rewritten sorted by id."""

    def __init__(self, path: str, columns: list[str]):
        self.path = path
        self.columns = columns
        self.lock = threading.Lock()
        self.done: set[int] = set()
        self.failed = 0
        existing = read_rows(path, columns)
        for row in existing:
            self.done.add(int(row["id"]))
            self.failed += bool(row["error"])
        self.previous = len(self.done)
        self._rewrite(existing)  # drops a torn last line so that appends start clean
        self.stream = open(path, "a", newline="", encoding="utf-8")
        self.writer = csv.writer(self.stream)

    def add(self, row: dict) -> bool:
        """Write a finished episode's row; False when its id was written already."""
        with self.lock:
            if row["id"] in self.done:
                return False
            values = {"id": row["id"], "repeat": row["repeat"], "worker": row.get("worker", ""),
                      "wall_time_s": row.get("wall_time_s"), "error": row.get("error", "")}
            values.update(row["params"])
            values.update(row.get("measures") or {})
            self.writer.writerow([_cell(values.get(column)) for column in self.columns])
            self.stream.flush()
            self.done.add(row["id"])
            self.failed += bool(row.get("error"))
            return True

    def _rewrite(self, rows: list[dict]) -> None:
        rows = sorted(rows, key=lambda row: int(row["id"]))
        temporary = self.path + ".tmp"
        with open(temporary, "w", newline="", encoding="utf-8") as stream:
            writer = csv.DictWriter(stream, fieldnames=self.columns)
            writer.writeheader()
            writer.writerows(rows)
        os.replace(temporary, self.path)

    def close(self) -> list[dict]:
        """Close the file and rewrite it sorted by id; returns its rows."""
        with self.lock:
            self.stream.close()
            rows = read_rows(self.path, self.columns)
            self._rewrite(rows)
            return sorted(rows, key=lambda row: int(row["id"]))


def read_rows(path: str, columns: list[str]) -> list[dict]:
    """The complete rows of an episodes.csv (one per id); [] when there is none."""
    if not os.path.isfile(path):
        return []
    with open(path, newline="", encoding="utf-8") as stream:
        reader = csv.reader(stream)
        header = next(reader, None)
        if header is None:
            return []
        if header != columns:
            raise SweepError(f"{path} has other columns than this sweep's ({', '.join(header)}); "
                             "it is not this sweep's output: pass another --out")
        rows, seen = [], set()
        for cells in reader:
            if len(cells) != len(columns) or not cells[0].isdigit() or int(cells[0]) in seen:
                continue  # a line torn by an interruption: that episode runs again
            seen.add(int(cells[0]))
            rows.append(dict(zip(columns, cells)))
        return rows


class Progress:
    """A bar on a terminal; elsewhere one line about every 10 %."""

    def __init__(self, total: int, done: int, results: Results, stream=sys.stderr):
        self.total, self.start_done, self.results, self.stream = total, done, results, stream
        self.tty = stream.isatty()
        self.start = time.monotonic()
        self.last_decile = done * 10 // max(total, 1)
        self.last_draw = 0.0

    def update(self, force: bool = False) -> None:
        done = len(self.results.done)
        elapsed = time.monotonic() - self.start
        text = f"{done}/{self.total} episodes, {self.results.failed} failed, {elapsed:.1f} s"
        if self.tty:
            now = time.monotonic()
            if force or now - self.last_draw > 0.1 or done == self.total:
                width = 30
                filled = width * done // max(self.total, 1)
                self.stream.write(f"\r{PROG}: [{'#' * filled}{'.' * (width - filled)}] {text}")
                self.stream.flush()
                self.last_draw = now
        else:
            decile = done * 10 // max(self.total, 1)
            if decile > self.last_decile or (force and done > self.start_done):
                self.stream.write(f"{PROG}: {text}\n")
                self.stream.flush()
                self.last_decile = decile

    def finish(self) -> None:
        if self.tty:
            self.update(force=True)
            self.stream.write("\n")
            self.stream.flush()


def run_local(tasks: list[dict], jobs: int, results: Results, progress: Progress) -> None:
    """Run the tasks in `jobs` threads, keeping at most 2 * jobs submitted so
    that an interruption leaves little queued."""
    executor = concurrent.futures.ThreadPoolExecutor(max_workers=jobs, thread_name_prefix="local")
    queue = iter(tasks)
    running: set[concurrent.futures.Future] = set()
    try:
        while True:
            while len(running) < 2 * jobs:
                task = next(queue, None)
                if task is None:
                    break
                running.add(executor.submit(run_episode, task))
            if not running:
                break
            finished, running = concurrent.futures.wait(running, timeout=0.5,
                                                        return_when=concurrent.futures.FIRST_COMPLETED)
            for future in finished:
                results.add(future.result())
            progress.update()
    except KeyboardInterrupt:
        for future in running:
            future.cancel()
        started = [future for future in running if not future.cancelled()]
        if started:
            sys.stderr.write(f"\n{PROG}: interrupted; finishing the {len(started)} running episode(s) "
                             "(Ctrl-C again to stop now)\n")
        try:
            for future in concurrent.futures.as_completed(started):
                results.add(future.result())
        except KeyboardInterrupt:
            raise Interrupted(abandoned=True) from None
        raise Interrupted(abandoned=False) from None
    finally:
        executor.shutdown(wait=False, cancel_futures=True)


def connect(address: str):
    """A Dask client of the scheduler at `address`, or a SweepError within about
    SCHEDULER_TIMEOUT_S seconds."""
    try:
        import distributed
    except ImportError:
        raise SweepError("--scheduler needs Dask's distributed package (apt install python3-distributed)") from None
    logging.getLogger("distributed").setLevel(logging.ERROR)
    try:
        return distributed.Client(address, timeout=SCHEDULER_TIMEOUT_S, set_as_default=False)
    except Exception as e:  # noqa: BLE001 - whatever the transport raises, the scheduler is not there
        raise SweepError(f"the Dask scheduler at {address} did not answer in {SCHEDULER_TIMEOUT_S} s "
                         f"({_one_line(e)}); start one with `dask-scheduler` and workers with "
                         f"`dask-worker {address}`") from None


def run_dask(client, tasks: list[dict], spec_hash: str, results: Results, progress: Progress) -> None:
    """Run the tasks on the cluster. A worker that dies has its tasks rerun by
    Dask elsewhere; each id is written once."""
    import distributed

    if not tasks:
        return
    if not client.scheduler_info().get("workers"):
        sys.stderr.write(f"{PROG}: the Dask scheduler has no workers yet; waiting for `dask-worker` to join\n")
    # Batches of episodes: about 8 per worker at least, at most 25 episodes
    # each, so that the scheduler's work per episode stays small and a worker
    # that dies loses little.
    workers = max(1, len(client.scheduler_info().get("workers", {})))
    size = max(1, min(25, -(-len(tasks) // (8 * workers))))
    batches = [tasks[i:i + size] for i in range(0, len(tasks), size)]
    keys = [f"servoloop-episodes-{spec_hash}-{batch[0]['id']}-{batch[-1]['id']}" for batch in batches]
    by_key = dict(zip(keys, batches))
    futures = client.map(run_batch, batches, key=keys, pure=False)
    pending = set(futures)
    try:
        for future in distributed.as_completed(futures, loop=client.loop):
            pending.discard(future)
            try:
                rows = future.result()
            except distributed.KilledWorker as e:
                rows = [{"id": task["id"], "params": task["params"], "repeat": task["repeat"], "measures": {},
                         "worker": "", "wall_time_s": None,
                         "error": f"the episode's Dask workers died each time it ran ({_one_line(e)})"}
                        for task in by_key[future.key]]
            except ModuleNotFoundError as e:
                package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
                raise SweepError(f"a Dask worker cannot import what an episode needs ({e}); start dask-worker "
                                 f"with PYTHONPATH={package} (where the servoloop package is)") from None
            except Exception as e:  # noqa: BLE001 - the cluster failed, not the episode
                raise SweepError(f"Dask could not run episodes {future.key}: {_one_line(e)}") from None
            for row in rows:
                results.add(row)
            future.release()
            progress.update()
    finally:
        if pending:
            client.cancel(list(pending))


def _resume_command(args) -> str:
    words = [args.spec, "--out", args.out, "--resume"]
    if args.scheduler:
        words += ["--scheduler", args.scheduler]
    return " ".join([PROG, *(shlex.quote(word) for word in words)])


def _check_out(args, spec, episode_list: list[dict]) -> tuple[list[dict], dict | None]:
    """Check --out against --resume, writing nothing. Returns the episodes (a
    resumed sweep's stored ones) and the sweep.json content to write (None
    when resuming)."""
    csv_path = os.path.join(args.out, "episodes.csv")
    state_path = os.path.join(args.out, "sweep.json")
    canonical = json.loads(json.dumps(spec.canonical))
    if args.resume:
        try:
            with open(state_path, encoding="utf-8") as stream:
                state = json.load(stream)
        except FileNotFoundError:
            raise SweepError(f"{args.out} holds no sweep to resume (no sweep.json); run without --resume") from None
        except (OSError, ValueError) as e:
            raise SweepError(f"{state_path} cannot be read ({e}); run again with another --out") from None
        stored = state.get("spec", {})
        if stored != canonical:
            changed = sorted(key for key in set(stored) | set(canonical) if stored.get(key) != canonical.get(key))
            raise SweepError(f"{args.spec} changed since the sweep in {args.out} started (changed: "
                             f"{', '.join(changed)}); --resume continues the same sweep: restore the spec or "
                             "pass another --out")
        return state["episodes"], None
    if read_rows_count(csv_path) > 0:
        raise SweepError(f"{csv_path} already holds episodes; pass --resume to continue that sweep or "
                         "another --out for a new one")
    return episode_list, {"spec_file": os.path.abspath(args.spec), "spec_hash": spec.hash, "spec": canonical,
                          "episodes": episode_list}


def _start_out(directory: str, state: dict | None) -> str:
    """Create --out (a new sweep: sweep.json, no episodes.csv); returns episodes.csv's path."""
    os.makedirs(directory, exist_ok=True)
    csv_path = os.path.join(directory, "episodes.csv")
    if state is not None:
        if os.path.exists(csv_path):
            os.remove(csv_path)  # a header without rows
        state_path = os.path.join(directory, "sweep.json")
        with open(state_path + ".tmp", "w", encoding="utf-8") as stream:
            json.dump(state, stream, indent=1)
            stream.write("\n")
        os.replace(state_path + ".tmp", state_path)
    return csv_path


def read_rows_count(path: str) -> int:
    try:
        with open(path, newline="", encoding="utf-8") as stream:
            return max(sum(1 for _ in csv.reader(stream)) - 1, 0)
    except FileNotFoundError:
        return 0


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog=PROG, description="Run a launch file's world over a grid and/or random samples of parameters; "
        "write one CSV row per episode and a plot per measure and parameter.")
    parser.add_argument("spec", help="the sweep spec (YAML: launch, duration, publish, vary, random, measure, ...)")
    parser.add_argument("--out", required=True, help="the output directory (episodes.csv, sweep.json, plots/)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="episodes at once in this process (default: the number of CPUs)")
    parser.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                        help="run the episodes on this Dask scheduler's workers instead")
    parser.add_argument("--resume", action="store_true",
                        help="continue the sweep in --out: run only the episodes not in its episodes.csv")
    return parser


def main(argv=None) -> int:
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else 2
    if args.jobs < 1:
        parser.print_usage(sys.stderr)
        sys.stderr.write(f"{PROG}: error: --jobs {args.jobs}: must be at least 1\n")
        return 2
    client = None
    try:
        spec = load_spec(args.spec)
        check_against_world(spec)
        episode_list, state = _check_out(args, spec, episodes(spec))
        if args.scheduler:
            client = connect(args.scheduler)
        csv_path = _start_out(args.out, state)
        columns = ["id", *spec.parameters, "repeat", *spec.measure, "worker", "wall_time_s", "error"]
        results = Results(csv_path, columns)
        todo = [task for task in make_tasks(spec, episode_list) if task["id"] not in results.done]
        if results.previous:
            print(f"{PROG}: resuming: {results.previous} of {len(episode_list)} episodes done, {len(todo)} to run",
                  file=sys.stderr)
        progress = Progress(len(episode_list), results.previous, results)
        start = time.monotonic()
        try:
            if client is not None:
                run_dask(client, todo, spec.hash, results, progress)
            else:
                run_local(todo, min(args.jobs, max(len(todo), 1)), results, progress)
        except KeyboardInterrupt as e:
            progress.finish()
            results.close()
            ran = len(results.done) - results.previous
            print(f"{PROG}: interrupted after {ran} episode(s) ({len(results.done)} of {len(episode_list)} in "
                  f"{csv_path}); continue with:\n  {_resume_command(args)}", file=sys.stderr)
            if getattr(e, "abandoned", False):
                # Exiting normally would wait for the abandoned episodes' threads.
                sys.stdout.flush()
                sys.stderr.flush()
                os._exit(130)
            return 130
        except SweepError as e:
            progress.finish()
            results.close()
            print(f"{PROG}: error: {e}\n{PROG}: {len(results.done)} of {len(episode_list)} episodes are in "
                  f"{csv_path}; once that is fixed, continue with:\n  {_resume_command(args)}", file=sys.stderr)
            return 2
        progress.finish()
        rows = results.close()
        elapsed = time.monotonic() - start
        ran = len(results.done) - results.previous
        failed = sum(1 for row in rows if row["error"])
        plots, note = plot_sweep(rows, spec.parameters, list(spec.measure), os.path.join(args.out, "plots"))
        if note:
            print(f"{PROG}: warning: {note}", file=sys.stderr)
        print(f"{PROG}: {ran} episode(s) ran in {elapsed:.1f} s"
              + (f" ({results.previous} done before)" if results.previous else "")
              + f"; {failed} of {len(rows)} failed")
        print(f"  results: {csv_path}")
        if plots:
            print(f"  plots:   {os.path.join(args.out, 'plots')} ({len(plots)} PNG)")
        return 1 if failed else 0
    except (SpecError, SweepError) as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"\n{PROG}: interrupted", file=sys.stderr)
        return 130
    finally:
        if client is not None:
            client.close(timeout=5)


if __name__ == "__main__":
    # Run as servoloop.sweep rather than __main__ so that Dask ships run_episode
    # by reference (workers import servoloop.sweep) instead of by value.
    from servoloop.sweep import main as _main

    sys.exit(_main())
