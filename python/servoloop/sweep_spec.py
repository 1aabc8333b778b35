"""The `servoloop sweep` spec: reading, checking and expanding it into episodes.

A sweep spec (YAML) names a launch file, how long each episode runs, what is
published during it, which parameters vary (a grid and/or random draws) and
what is measured. Everything that can be wrong with it is found here, before
any episode runs: the keys and their types, and, against one probe world built
from the launch file, the parameter paths, the topics and the message fields
(so that a typo costs one clear message instead of a sweep full of failed
rows). The episode list is built once, in the client, with the random draws
made in a fixed order from the seed, so a local run and a Dask run of the same
spec run the very same episodes.
"""
from __future__ import annotations

import dataclasses
import difflib
import hashlib
import itertools
import json
import math
import os
import re

import numpy as np
import yaml

from . import Error, World

SPEC_KEYS = ("launch", "duration", "backend", "publish", "vary", "random", "samples", "seed", "repeat", "measure")
PUBLISH_KEYS = ("topic", "value", "time", "type")
MEASURE_KEYS = ("topic", "field", "reduce")
REDUCES = ("last", "first", "min", "max", "mean", "rms")
DISTRIBUTIONS = ("uniform", "normal")
# The CSV's own columns; a measure may not take one of these names.
FIXED_COLUMNS = ("id", "repeat", "worker", "wall_time_s", "error")

# position[0], pose.pose.position.x, data[-1], a.b[2][0]
_NAME = r"[A-Za-z_][A-Za-z0-9_]*"
_FIELD_RE = re.compile(rf"^{_NAME}(\[-?\d+\])*(\.{_NAME}(\[-?\d+\])*)*$")
_SEGMENT_RE = re.compile(rf"({_NAME})|\[(-?\d+)\]")
# Measure names become CSV columns and plot file names.
_MEASURE_NAME_RE = re.compile(r"^[A-Za-z0-9_.-]+$")


class SpecError(Exception):
    """A problem with the spec, named by the spec file and the key it is at."""

    def __init__(self, spec_file: str, key: str, message: str):
        super().__init__(f"{spec_file}: {key}: {message}" if key else f"{spec_file}: {message}")


class FieldError(Exception):
    """A field path that does not lead to a value in a message."""


@dataclasses.dataclass
class Spec:
    """A checked spec. `canonical` is its JSON-able content (absolute launch
    path, defaults filled in) that sweep.json stores and --resume compares."""

    file: str
    launch: str
    duration: float
    backend: str | None
    publish: list[dict]
    vary: dict[str, list]
    random: dict[str, dict]
    samples: int | None
    seed: int
    repeat: int
    measure: dict[str, dict]

    @property
    def canonical(self) -> dict:
        return {
            "launch": self.launch,
            "duration": self.duration,
            "backend": self.backend,
            "publish": self.publish,
            "vary": self.vary,
            "random": self.random,
            "samples": self.samples,
            "seed": self.seed,
            "repeat": self.repeat,
            "measure": self.measure,
        }

    @property
    def hash(self) -> str:
        """A short digest of the canonical content: Dask keys and sweep.json use it."""
        text = json.dumps(self.canonical, separators=(",", ":"), allow_nan=False)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    @property
    def parameters(self) -> list[str]:
        """The varied and randomly drawn parameters, in the CSV's column order."""
        return list(self.vary) + list(self.random)


def _closest(word: str, candidates, n: int = 3) -> str:
    matches = difflib.get_close_matches(word, list(candidates), n=n, cutoff=0.6)
    return f"; closest: {', '.join(matches)}" if matches else ""


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _check_keys(spec_file: str, where: str, mapping: dict, known) -> None:
    for key in mapping:
        if key not in known:
            hint = difflib.get_close_matches(str(key), known, n=1)
            suggestion = f"; did you mean '{hint[0]}'?" if hint else ""
            raise SpecError(spec_file, where + str(key),
                            f"unknown key{suggestion} (the keys are: {', '.join(known)})")


def parse_field(field: str) -> list:
    """'pose.position[0]' -> ['pose', 'position', 0]."""
    if not isinstance(field, str) or not _FIELD_RE.match(field):
        raise FieldError(f"'{field}' is not a field path (names joined by dots, with [index]: "
                         "position[0], pose.pose.position.x)")
    return [name if name else int(index) for name, index in _SEGMENT_RE.findall(field)]


def _describe(path: list) -> str:
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else part)
    return text


def extract(msg, path: list, type_name: str = "the message"):
    """The value at `path` in a message dict; a FieldError says what is there instead."""
    value = msg
    for depth, part in enumerate(path):
        where = _describe(path[:depth]) or type_name
        if isinstance(part, int):
            if not isinstance(value, list):
                raise FieldError(f"{where} is not a list; [{part}] cannot index it")
            if not -len(value) <= part < len(value):
                raise FieldError(f"{where} has {len(value)} element(s); [{part}] is out of range")
            value = value[part]
        else:
            if not isinstance(value, dict):
                raise FieldError(f"{where} has no fields; '{part}' cannot be in it")
            if part not in value:
                raise FieldError(f"{where} has no field '{part}'{_closest(part, value, 1)}; "
                                 f"its fields are: {', '.join(sorted(value))}")
            value = value[part]
    if isinstance(value, list):
        raise FieldError(f"{_describe(path)} is a list of {len(value)}; pick one element, "
                         f"e.g. {_describe(path)}[0]")
    if isinstance(value, dict):
        raise FieldError(f"{_describe(path)} has fields {', '.join(sorted(value))}; pick one, "
                         f"e.g. {_describe(path)}.{sorted(value)[0] if value else 'x'}")
    return value


def reduce_values(values: list, how: str):
    """One number (or, for first/last, one value) from a measure's values in time order."""
    if how == "first":
        return values[0]
    if how == "last":
        return values[-1]
    for value in values:
        if not _is_number(value):
            raise FieldError(f"reduce '{how}' needs numbers; got {value!r}")
    array = np.asarray(values, dtype=float)
    if how == "min":
        return float(np.min(array))
    if how == "max":
        return float(np.max(array))
    if how == "mean":
        return float(np.mean(array))
    if how == "rms":
        return float(np.sqrt(np.mean(np.square(array))))
    raise ValueError(f"unknown reduce '{how}'")


def _number(spec_file, key, value, what, minimum=None, integer=False, positive=False):
    if not _is_number(value) or (integer and not isinstance(value, int)):
        raise SpecError(spec_file, key, f"{value!r} is not {'an integer' if integer else 'a number'} ({what})")
    if not math.isfinite(value):
        raise SpecError(spec_file, key, f"{value!r} is not a finite number ({what})")
    if positive and value <= 0:
        raise SpecError(spec_file, key, f"{value!r} must be greater than 0 ({what})")
    if minimum is not None and value < minimum:
        raise SpecError(spec_file, key, f"{value!r} must be at least {minimum} ({what})")
    return value


def _json_value(spec_file, key, value):
    """A value as it will cross into the world (JSON), rejecting what JSON cannot carry."""
    try:
        return json.loads(json.dumps(value, allow_nan=False))
    except (TypeError, ValueError) as e:
        raise SpecError(spec_file, key, f"{value!r} cannot be a parameter or message value ({e})") from None


def _parameter_path(spec_file, section, path):
    if not isinstance(path, str) or not path.startswith("/"):
        raise SpecError(spec_file, section, f"{path!r} is not a full parameter path (like /robot/controller/pid/p)")
    return path


def load_spec(spec_file: str) -> Spec:
    """Read and check the spec's keys and values (not yet against a world)."""
    try:
        with open(spec_file, encoding="utf-8") as stream:
            data = yaml.safe_load(stream)
    except OSError as e:
        raise SpecError(spec_file, "", f"cannot be read ({e.strerror})") from None
    except yaml.YAMLError as e:
        raise SpecError(spec_file, "", f"is not valid YAML ({' '.join(str(e).split())})") from None
    if not isinstance(data, dict):
        raise SpecError(spec_file, "", "must be a mapping with launch:, duration:, vary: and measure:")
    _check_keys(spec_file, "", data, SPEC_KEYS)
    for key in ("launch", "duration", "measure"):
        if data.get(key) is None:
            raise SpecError(spec_file, key, "missing (a sweep needs launch:, duration: and measure:)")

    launch = data["launch"]
    if not isinstance(launch, str) or not launch:
        raise SpecError(spec_file, "launch", f"{launch!r} is not a path to a launch file")
    launch = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(spec_file)), launch))
    if not os.path.isfile(launch):
        raise SpecError(spec_file, "launch", f"{launch} does not exist (a relative path is relative to the spec file)")

    duration = float(_number(spec_file, "duration", data["duration"], "simulated seconds per episode", positive=True))
    backend = data.get("backend")
    if backend is not None and (not isinstance(backend, str) or not backend):
        raise SpecError(spec_file, "backend", f"{backend!r} is not a backend name (bullet, mujoco, mock)")

    publish = []
    entries = data.get("publish") or []
    if not isinstance(entries, list):
        raise SpecError(spec_file, "publish", "must be a list of {topic: ..., value: ..., time: ...}")
    for index, entry in enumerate(entries):
        key = f"publish[{index}]"
        if not isinstance(entry, dict):
            raise SpecError(spec_file, key, "must be a mapping {topic: ..., value: ..., time: ...}")
        _check_keys(spec_file, key + ".", entry, PUBLISH_KEYS)
        if not isinstance(entry.get("topic"), str) or not entry["topic"].startswith("/"):
            raise SpecError(spec_file, key + ".topic", f"{entry.get('topic')!r} is not a topic name (/robot/...)")
        if "value" not in entry:
            raise SpecError(spec_file, key, "missing 'value': the message to publish, e.g. value: 1.0")
        time_s = float(_number(spec_file, key + ".time", entry.get("time", 0.0), "s of simulated time", minimum=0))
        if time_s > duration:
            raise SpecError(spec_file, key + ".time", f"{time_s} s is after the episode's end (duration {duration} s)")
        kind = entry.get("type") or ""
        if not isinstance(kind, str):
            raise SpecError(spec_file, key + ".type", f"{kind!r} is not a message type (like std_msgs/Float64)")
        publish.append({"topic": entry["topic"], "value": _json_value(spec_file, key + ".value", entry["value"]),
                        "time": time_s, "type": kind})

    vary = {}
    grid = data.get("vary") or {}
    if not isinstance(grid, dict):
        raise SpecError(spec_file, "vary", "must map parameter paths to lists of values")
    for path, values in grid.items():
        key = f"vary: {path}"
        _parameter_path(spec_file, "vary", path)
        if not isinstance(values, list) or not values:
            raise SpecError(spec_file, key, "must be a non-empty list of values, e.g. [5.0, 10.0, 20.0]")
        vary[path] = [_json_value(spec_file, key, value) for value in values]

    random = {}
    draws = data.get("random") or {}
    if not isinstance(draws, dict):
        raise SpecError(spec_file, "random",
                        "must map parameter paths to {uniform: [low, high]} or {normal: [mean, stddev]}")
    for path, dist in draws.items():
        key = f"random: {path}"
        _parameter_path(spec_file, "random", path)
        if path in vary:
            raise SpecError(spec_file, key, "is also under vary:; a parameter is either varied or drawn")
        if not isinstance(dist, dict) or len(dist) != 1:
            raise SpecError(spec_file, key, "must be {uniform: [low, high]} or {normal: [mean, stddev]}")
        (name, bounds), = dist.items()
        if name not in DISTRIBUTIONS:
            raise SpecError(spec_file, key, f"unknown distribution '{name}'{_closest(str(name), DISTRIBUTIONS, 1)} "
                                            f"(the distributions are: {', '.join(DISTRIBUTIONS)})")
        if (not isinstance(bounds, list) or len(bounds) != 2
                or not all(_is_number(b) and math.isfinite(b) for b in bounds)):
            raise SpecError(spec_file, key, f"{name}: needs two finite numbers, "
                                            f"{'[low, high]' if name == 'uniform' else '[mean, stddev]'}")
        first, second = float(bounds[0]), float(bounds[1])
        if name == "uniform" and not first < second:
            raise SpecError(spec_file, key, f"uniform: [{first}, {second}]: low must be less than high")
        if name == "normal" and second < 0:
            raise SpecError(spec_file, key, f"normal: [{first}, {second}]: stddev must not be negative")
        random[path] = {name: [first, second]}

    samples = None
    if data.get("samples") is not None:
        if not random:
            raise SpecError(spec_file, "samples", "draws nothing without random: (the parameters to draw)")
        samples = _number(spec_file, "samples", data["samples"], "random draws", integer=True, minimum=1)
    elif random:
        samples = 1
    seed = _number(spec_file, "seed", data.get("seed", 0), "the random seed", integer=True, minimum=0)
    repeat = _number(spec_file, "repeat", data.get("repeat", 1), "runs of each episode", integer=True, minimum=1)

    measure = {}
    measures = data["measure"]
    if not isinstance(measures, dict) or not measures:
        raise SpecError(spec_file, "measure", "must map column names to {topic: ..., field: ..., reduce: ...}")
    columns = set(FIXED_COLUMNS) | set(vary) | set(random)
    for name, entry in measures.items():
        key = f"measure: {name}"
        if not isinstance(name, str) or not _MEASURE_NAME_RE.match(name):
            raise SpecError(spec_file, key, "a measure's name is a CSV column and a file name: letters, digits, _ . -")
        if name in columns:
            raise SpecError(spec_file, key, f"'{name}' is already a column of episodes.csv; rename the measure")
        if not isinstance(entry, dict):
            raise SpecError(spec_file, key, "must be {topic: ..., field: ..., reduce: ...}")
        _check_keys(spec_file, key + ": ", entry, MEASURE_KEYS)
        topic = entry.get("topic")
        if not isinstance(topic, str) or not topic.startswith("/"):
            raise SpecError(spec_file, key + ": topic", f"{topic!r} is not a topic name (/robot/...)")
        if "field" not in entry:
            raise SpecError(spec_file, key, "missing 'field': the message field to measure, e.g. position[0]")
        try:
            parse_field(entry["field"])
        except FieldError as e:
            raise SpecError(spec_file, key + ": field", str(e)) from None
        how = entry.get("reduce", "last")
        if how not in REDUCES:
            raise SpecError(spec_file, key + ": reduce", f"unknown reduce '{how}'{_closest(str(how), REDUCES, 1)} "
                                                         f"(the reduces are: {', '.join(REDUCES)})")
        measure[name] = {"topic": topic, "field": entry["field"], "reduce": how}

    return Spec(file=spec_file, launch=launch, duration=duration, backend=backend, publish=publish, vary=vary,
                random=random, samples=samples, seed=seed, repeat=repeat, measure=measure)


def flatten_params(tree, prefix: str = "") -> tuple[dict, set]:
    """get_param("/")'s tree -> ({/full/path: value}, {namespace paths})."""
    leaves, namespaces = {}, set()
    for name, value in tree.items():
        path = f"{prefix}/{name}"
        if isinstance(value, dict) and value:
            namespaces.add(path)
            inner, deeper = flatten_params(value, path)
            leaves.update(inner)
            namespaces |= deeper
        else:
            leaves[path] = value
    return leaves, namespaces


def _unknown_parameter(spec: Spec, section: str, path: str, leaves: dict, namespaces: set) -> SpecError:
    key = f"{section}: {path}"
    if path in namespaces:
        inside = sorted(p for p in leaves if p.startswith(path + "/"))
        return SpecError(spec.file, key, f"is a namespace, not a parameter; its parameters: {', '.join(inside[:10])}")
    hint = _closest(path, leaves)
    if not hint:
        # No near spelling: name what the deepest existing namespace on the path holds.
        parent = path.rsplit("/", 1)[0]
        while parent and parent not in namespaces:
            parent = parent.rsplit("/", 1)[0]
        if parent:
            inside = sorted(p.rsplit("/", 1)[1] for p in leaves if p.rsplit("/", 1)[0] == parent)
            hint = f"; the parameters in {parent} are: {', '.join(inside)}" if inside else ""
    return SpecError(spec.file, key, f"is not a parameter of {spec.launch}{hint}")


def check_against_world(spec: Spec) -> None:
    """Check parameter paths, topics and fields against a probe world built from
    the launch file, run (with the spec's publications) until every measured
    topic has published once."""
    try:
        world = World(spec.launch, backend=spec.backend, log_level="warn")
    except Error as e:
        key = "backend" if spec.backend and "backend" in str(e) else "launch"
        raise SpecError(spec.file, key, " ".join(str(e).split())) from None
    with world:
        leaves, namespaces = flatten_params(world.get_param("/"))
        for section, paths in (("vary", spec.vary), ("random", spec.random)):
            for path in paths:
                if path not in leaves:
                    raise _unknown_parameter(spec, section, path, leaves, namespaces)
        topics = world.topics
        for index, entry in enumerate(spec.publish):
            if entry["topic"] not in topics:
                raise SpecError(spec.file, f"publish[{index}].topic",
                                f"{entry['topic']} is not a topic of the world{_closest(entry['topic'], topics)}")
        for name, entry in spec.measure.items():
            if entry["topic"] not in topics:
                raise SpecError(spec.file, f"measure: {name}: topic",
                                f"{entry['topic']} is not a topic of the world{_closest(entry['topic'], topics)}")

        first = {}
        wanted = {entry["topic"] for entry in spec.measure.values()}
        for topic in wanted:
            world.subscribe(topic)
        pending = sorted(enumerate(spec.publish), key=lambda item: item[1]["time"])
        while True:
            while pending and pending[0][1]["time"] <= world.time:
                index, entry = pending.pop(0)
                try:
                    world.publish(entry["topic"], entry["value"], entry["type"])
                except Error as e:
                    raise SpecError(spec.file, f"publish[{index}]", " ".join(str(e).split())) from None
            for topic in wanted - set(first):
                messages = world.subscribe(topic)
                if messages:
                    first[topic] = messages[0]
            if len(first) == len(wanted) or world.time >= spec.duration - 1e-9:
                break
            until = min(spec.duration, world.time + 0.05, pending[0][1]["time"] if pending else math.inf)
            world.step(max(until - world.time, world.time_step))

    for name, entry in spec.measure.items():
        key = f"measure: {name}"
        message = first.get(entry["topic"])
        if message is None:
            raise SpecError(spec.file, key + ": topic",
                            f"{entry['topic']} published nothing in {spec.duration} s of a probe episode")
        try:
            value = extract(message["msg"], parse_field(entry["field"]), message.get("type") or "the message")
        except FieldError as e:
            raise SpecError(spec.file, key + ": field", f"'{entry['field']}': {e}") from None
        if entry["reduce"] not in ("first", "last") and not _is_number(value):
            raise SpecError(spec.file, key + ": reduce",
                            f"'{entry['reduce']}' needs a number; {entry['field']} is {value!r}")


def episodes(spec: Spec) -> list[dict]:
    """Every episode, {id, params, repeat}: the grid in key order (cartesian
    product), then the random samples (drawn in this order, parameter by
    parameter, from numpy's default_rng(seed)), then the repeats."""
    rng = np.random.default_rng(spec.seed)
    grid = itertools.product(*spec.vary.values()) if spec.vary else [()]
    result = []
    for point in grid:
        fixed = dict(zip(spec.vary, point))
        draws = [{}]
        if spec.random:
            draws = []
            for _ in range(spec.samples):
                drawn = {}
                for path, dist in spec.random.items():
                    (name, (first, second)), = dist.items()
                    value = rng.uniform(first, second) if name == "uniform" else rng.normal(first, second)
                    drawn[path] = float(value)
                draws.append(drawn)
        for drawn in draws:
            for repeat in range(spec.repeat):
                result.append({"id": len(result), "params": {**fixed, **drawn}, "repeat": repeat})
    return result
