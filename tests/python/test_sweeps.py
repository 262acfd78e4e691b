"""tumble.bench and tumble.stability: the rows of the command line's results.csv and
stability.csv as dicts, the same numbers as the CSVs the command writes for the same input
(apart from the timings, which differ between two runs)."""

import csv
import os
import signal
import subprocess
import sys
import tempfile
import textwrap
import time

import pytest

import tumble
from conftest import SOURCE

SPIN = {"name": "spin", "duration": 0.2, "dt": 0.01,
        "bodies": [{"name": "box", "inertia": {"principal": [1.0, 2.0, 3.0]}, "mass": 1.0,
                    "angular_velocity": [0.1, 2.0, 0.1]}]}
# The columns that differ between two runs of the same bench: the clock and the core.
TIMINGS = {"seconds_median", "seconds_min", "seconds_max", "ns_per_step", "core"}


def same(value, text):
    """Whether a row's value is the CSV field `text`: the same double, int, text, or empty."""
    if value is None:
        return text == ""
    if isinstance(value, float):
        return value == float(text) or (value != value and text.lower() == "nan")
    return str(value) == text


def csv_rows(path):
    with open(path, newline="") as file:
        return list(csv.DictReader(file))


def test_bench_rows_are_the_results_csv(cli, tmp_path):
    scene = tmp_path / "spin.json"
    import json
    scene.write_text(json.dumps(SPIN))
    status, _, err = cli("bench", scene, "--integrators", "rk4,splitting", "--dts",
                         "0.01,0.005", "--repeat", "1", "-o", tmp_path / "out")
    assert status == 0, err
    expected = csv_rows(tmp_path / "out" / "results.csv")
    rows = tumble.bench([scene], integrators=["rk4", "splitting"], dts=[0.01, 0.005], repeat=1)
    assert len(rows) == len(expected) == 4
    for ours, theirs in zip(rows, expected):
        assert list(ours) == list(theirs)
        for key, text in theirs.items():
            if key not in TIMINGS:  # they differ between two runs
                assert same(ours[key], text), key
    assert [r["integrator"] for r in rows] == ["rk4", "rk4", "splitting", "splitting"]


def test_stability_rows_are_the_stability_csv(cli, tmp_path):
    status, _, err = cli("stability", "--suite", "quick", "--cases", "needle", "--integrators",
                         "rk4,splitting4", "-o", tmp_path / "out")
    assert status == 0, err
    expected = csv_rows(tmp_path / "out" / "stability.csv")
    rows = tumble.stability(suite="quick", cases=["needle"], integrators=["rk4", "splitting4"])
    assert len(rows) == len(expected) > 0
    for ours, theirs in zip(rows, expected):
        assert list(ours) == list(theirs)
        for key, text in theirs.items():
            if "second" not in key:
                assert same(ours[key], text), key


def test_sweeps_raise_input_errors_with_the_command_lines_message():
    with pytest.raises(tumble.InputError, match="integrator"):
        tumble.bench([SOURCE / "assets" / "scenes" / "t_handle_flip.json"],
                     integrators=["euler9"])
    with pytest.raises(tumble.InputError, match="suite"):
        tumble.stability(suite="nope")


def test_ctrl_c_stops_a_long_bench_and_its_child():
    script = textwrap.dedent("""
        import sys, tumble
        scene = {"duration": 1e5, "dt": 1e-4,
                 "bodies": [{"inertia": {"principal": [1, 2, 3]}, "mass": 1,
                             "angular_velocity": [1, 2, 3]}]}
        print("running", flush=True)
        try:
            tumble.bench([scene], integrators=["rk4"], dts=[1e-4], repeat=1)
        except KeyboardInterrupt:
            print("interrupted", flush=True)
            sys.exit(7)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, cwd=tempfile.mkdtemp())
    try:
        assert child.stdout.readline() == "running\n"
        time.sleep(1.0)  # the bench is running in its child
        benches = [pid for pid in _children_of(child.pid)
                   if os.readlink("/proc/%d/exe" % pid).endswith("/tumble")]
        assert len(benches) == 1
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)  # to Python alone, not to its child
        out, err = child.communicate(timeout=10)
        waited = time.monotonic() - sent
    finally:
        if child.poll() is None:
            child.kill()
    assert child.returncode == 7, err
    assert out == "interrupted\n"
    assert waited < 2.0
    # The bench's process is not left behind, running on.
    assert not os.path.exists("/proc/%d" % benches[0])


def _children_of(parent):
    found = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            stat = open("/proc/%s/stat" % name).read()
        except OSError:
            continue
        if int(stat[stat.rindex(")") + 2:].split()[1]) == parent:
            found.append(int(name))
    return found
