"""tumble: rigid bodies whose mass properties come from real meshes.

The functions here are the library calls the `tumble` command line makes, with numpy arrays in
and out (docs/python.md). Units are SI (metres, kilograms, seconds); quaternions are
(w, x, y, z); principal axes are the COLUMNS of a rotation matrix. Bad input raises
tumble.InputError (a ValueError) with the command line's one-line message. Nothing is printed:
warnings come back in the results.

Rendering runs the `tumble` executable in a child process (render, compare), so the module
never loads OpenGL.
"""

import csv
import json
import os
import pathlib
import subprocess
import tempfile

from ._tumble import *  # noqa: F401,F403  (the compiled library calls)
from ._tumble import InputError, _executable_candidates

__all__ = [
    "InputError",
    "RunBlewUp",
    "MassProperties",
    "inspect",
    "mass_properties",
    "primitive",
    "RobotInertials",
    "inertials",
    "Trajectory",
    "simulate",
    "integrators",
    "bench",
    "stability",
    "render",
    "compare",
    "executable",
]


class RunBlewUp(RuntimeError):
    """A render or compare whose simulation blew up (exit status 3): its output was still
    written, at `output`, and the message says when and how."""

    def __init__(self, message, output):
        super().__init__(message)
        self.output = output


def executable():
    """The `tumble` executable render and compare run: $TUMBLE_EXECUTABLE when set, else the
    one of the build tree this module was built in, else the installed one."""
    given = os.environ.get("TUMBLE_EXECUTABLE")
    candidates = ([given] if given else []) + list(_executable_candidates())
    for candidate in candidates:
        if candidate and os.access(candidate, os.X_OK) and os.path.isfile(candidate):
            return candidate
    raise FileNotFoundError("the tumble executable was not found (looked for " +
                            ", ".join(c for c in candidates if c) + ")")


def _option_flags(options):
    """Keyword arguments as command-line options: size="640x360" -> --size 640x360, True -> the
    bare flag, False and None -> left out, a list -> comma-separated."""
    flags = []
    for name, value in options.items():
        flag = "--" + name.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            flags.append(flag)
        elif isinstance(value, (list, tuple)):
            flags += [flag, ",".join(str(v) for v in value)]
        else:
            flags += [flag, str(value)]
    return flags


def _run_child(argv):
    """Runs `argv` to its end and returns its CompletedProcess (text output captured). On
    Ctrl-C or any other exception the child is killed and reaped before the exception goes on,
    so no `tumble` is left running."""
    process = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    try:
        out, err = process.communicate()
    except BaseException:
        process.kill()
        process.wait()
        raise
    return subprocess.CompletedProcess(argv, process.returncode, out, err)


def _error_of(run, command):
    """The exception of a `tumble COMMAND` that ended with a non-zero status."""
    message = run.stderr.strip().splitlines()[-1] if run.stderr.strip() else ""
    prefix = "tumble " + command + ": error: "
    if run.returncode == 1:
        return InputError(message[len(prefix):] if message.startswith(prefix) else message)
    if run.returncode == 130:
        return KeyboardInterrupt(message)
    return RuntimeError(message or "tumble %s ended with status %d" % (command, run.returncode))


def _csv_value(text):
    """A CSV field as the number it writes (int, float: the same double, 17 digits), None when
    empty, else the text."""
    if text == "":
        return None
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


def _run_sweep(command, scenes, csv_name, options):
    """Runs `tumble COMMAND SCENES... -o TMP OPTIONS` in a temporary folder and returns the rows
    of TMP/CSV_NAME as dicts (the folder is removed). Scenes given as dicts are written as files
    in the working directory for the length of the run."""
    written = []
    try:
        paths = []
        for scene in scenes:
            if isinstance(scene, dict):
                handle, name = tempfile.mkstemp(prefix=".tumble-scene-", suffix=".json", dir=".")
                written.append(name)
                with os.fdopen(handle, "w") as file:
                    json.dump(scene, file)
                paths.append(name)
            else:
                paths.append(os.fspath(scene))
        with tempfile.TemporaryDirectory(prefix="tumble-" + command + "-") as folder:
            output = os.path.join(folder, "out")
            # One shard of one: the whole sweep, its CSV without the plots and the report
            # (the same rows, and no gnuplot needed).
            argv = [executable(), command, *paths, "-o", output, "--shard", "0/1"]
            argv += _option_flags(options)
            run = _run_child(argv)
            if run.returncode != 0:
                raise _error_of(run, command)
            with open(os.path.join(output, csv_name), newline="") as file:
                return [{key: _csv_value(value) for key, value in row.items()}
                        for row in csv.DictReader(file)]
    finally:
        for name in written:
            os.unlink(name)


def bench(scenes, *, integrators=None, dts=None, tolerances=None, duration=None, repeat=None,
          jobs=None):
    """Error against run time for every integrator and step size (`tumble bench`): the rows of
    its results.csv as dicts, one per run, numbers as the CSV writes them (s, rad, m; the
    columns are docs/bench.md's). scenes: a list of scene paths or dicts; integrators, dts,
    tolerances: lists (the flags' comma-separated lists); duration s; repeat: timed runs per
    case; jobs: cases at once. Runs the `tumble` executable (its report and plots are not kept).
    Raises InputError for bad input, KeyboardInterrupt on Ctrl-C."""
    return _run_sweep("bench", scenes, "results.csv",
                      dict(integrators=integrators, dts=dts, tolerances=tolerances,
                           duration=duration, repeat=repeat, jobs=jobs))


def stability(scenes=(), *, suite=None, integrators=None, cases=None, dts=None):
    """Stiff and extreme cases under every integrator and step (`tumble stability`): the rows of
    its stability.csv as dicts, one per run, each with its outcome (stable, drifting, damped,
    wrong, blew up) and errors (docs/stability.md). suite: "standard" or "quick"; cases,
    integrators, dts: lists; scenes: scene paths or dicts added as cases. Runs the `tumble`
    executable. Raises InputError for bad input, KeyboardInterrupt on Ctrl-C."""
    return _run_sweep("stability", scenes, "stability.csv",
                      dict(suite=suite, integrators=integrators, cases=cases, dts=dts))


def _run_drawing(command, scene, output, options):
    """Runs `tumble COMMAND SCENE -o OUTPUT OPTIONS` and returns OUTPUT as a Path. A scene given
    as a dict is written next to the working directory's files (so that its relative mesh paths
    mean what they mean in Python) for the length of the run."""
    output = pathlib.Path(output)
    written = None
    if isinstance(scene, dict):
        handle, written = tempfile.mkstemp(prefix=".tumble-scene-", suffix=".json", dir=".")
        with os.fdopen(handle, "w") as file:
            json.dump(scene, file)
        scene = written
    try:
        argv = [executable(), command, os.fspath(scene), "-o", os.fspath(output)]
        argv += _option_flags(options)
        run = _run_child(argv)
    finally:
        if written:
            os.unlink(written)
    message = run.stderr.strip().splitlines()[-1] if run.stderr.strip() else ""
    prefix = "tumble " + command + ": error: "
    if run.returncode == 0:
        return output
    if run.returncode == 1:
        raise InputError(message[len(prefix):] if message.startswith(prefix) else message)
    if run.returncode == 3:
        raise RunBlewUp(message, output)
    if run.returncode == 130:
        raise KeyboardInterrupt(message)
    raise RuntimeError(message or "tumble %s ended with status %d" % (command, run.returncode))


def render(scene, output, **options):
    """Renders `scene` (a scene file's path or a scene as a dict) to `output` (.mp4, .webm, .gif
    or a folder for PNG frames) with `tumble render`; options as its flags (size="640x360",
    fps=30, frames="0:120", aa="off", no_overlay=True). Returns the output's path. Raises
    InputError for bad input, RunBlewUp when the run blew up (the output is written)."""
    return _run_drawing("render", scene, output, options)


def compare(scene, output, integrators, **options):
    """The same scene under several integrators in one video (`tumble compare`): integrators a
    list of names (tumble.integrators() lists them), options as the command's flags
    (layout="grid"). Returns the output's path."""
    return _run_drawing("compare", scene, output, dict(options, integrators=integrators))
