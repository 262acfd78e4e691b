"""tumble.simulate, Trajectory and tumble.integrators against the command line's output for the
same scene (`tumble simulate --csv --json`: the CSV byte for byte, the summary to the last
digit) and against closed forms; Ctrl-C in a long run."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import tumble
from conftest import SOURCE

T_HANDLE = SOURCE / "assets" / "scenes" / "t_handle_flip.json"
# What differs between two runs of the same scene: the clock and where the CSV went.
RUN_DEPENDENT = ("wall_seconds", "steps_per_second", "csv", "csv_rows")


def falling_box(**changes):
    """A box (principal moments 1, 2, 3 kg m^2, 2 kg) thrown up and spinning in gravity."""
    scene = {"name": "falling", "duration": 1.0, "dt": 0.01, "integrator": "rk4",
             "gravity": [0.0, 0.0, -9.81],
             "bodies": [{"name": "box", "inertia": {"principal": [1.0, 2.0, 3.0]}, "mass": 2.0,
                         "position": [1.0, 2.0, 3.0], "velocity": [0.5, 0.0, 4.0],
                         "angular_velocity": [0.0, 0.0, 2.0]}]}
    scene.update(changes)
    return scene


def test_the_csv_and_the_summary_are_the_command_lines(cli, tmp_path):
    csv = tmp_path / "cli.csv"
    status, out, err = cli("simulate", T_HANDLE, "--duration", "2", "--every", "7", "--csv", csv,
                           "--json")
    assert status == 0, err
    trajectory = tumble.simulate(str(T_HANDLE), duration=2.0, every=7)
    ours = tmp_path / "python.csv"
    trajectory.to_csv(ours)
    assert ours.read_bytes() == csv.read_bytes()
    expected = {k: v for k, v in json.loads(out).items() if k not in RUN_DEPENDENT}
    summary = {k: v for k, v in trajectory.summary.items() if k not in RUN_DEPENDENT}
    assert summary == expected
    assert trajectory.blew_up is False and trajectory.blow_up is None


def test_the_arrays_are_the_csvs_columns(cli, tmp_path):
    trajectory = tumble.simulate(str(T_HANDLE), duration=1.0, every=10)
    csv = tmp_path / "t.csv"
    trajectory.to_csv(csv)
    columns = np.loadtxt(csv, delimiter=",", skiprows=1, usecols=[0] + list(range(2, 19)))
    n = len(trajectory)
    assert trajectory.t.shape == (n,) and trajectory.position.shape == (n, 1, 3)
    assert trajectory.orientation.shape == (n, 1, 4) and trajectory.energy.shape == (n,)
    assert trajectory.body_names == ["t-handle"]
    np.testing.assert_array_equal(trajectory.t, columns[:, 0])
    np.testing.assert_array_equal(trajectory.position[:, 0], columns[:, 1:4])
    np.testing.assert_array_equal(trajectory.orientation[:, 0], columns[:, 4:8])
    np.testing.assert_array_equal(trajectory.velocity[:, 0], columns[:, 8:11])
    np.testing.assert_array_equal(trajectory.angular_velocity[:, 0], columns[:, 11:14])
    np.testing.assert_array_equal(trajectory.angular_momentum[:, 0], columns[:, 14:17])
    np.testing.assert_array_equal(trajectory.energy, columns[:, 17])
    # The scene's 1000 steps of 1 ms, every 10th and the first: 101 rows.
    assert json.loads(T_HANDLE.read_text())["dt"] == 0.001
    assert n == 101


def test_a_thrown_box_follows_the_parabola_and_keeps_its_spin():
    trajectory = tumble.simulate(falling_box(), every=5)
    t = trajectory.t
    np.testing.assert_allclose(t, np.arange(0, 101, 5) * 0.01, rtol=0, atol=1e-12)
    expected = np.stack([1.0 + 0.5 * t, 2.0 + 0 * t, 3.0 + 4.0 * t - 0.5 * 9.81 * t * t], axis=1)
    # RK4 integrates a quadratic exactly: rounding only.
    np.testing.assert_allclose(trajectory.position[:, 0], expected, rtol=0, atol=1e-12)
    np.testing.assert_allclose(trajectory.velocity[:, 0, 2], 4.0 - 9.81 * t, atol=1e-12)
    # A spin about the principal axis of the largest moment stays one: omega = (0, 0, 2).
    np.testing.assert_allclose(trajectory.angular_velocity[:, 0],
                               np.tile([0.0, 0.0, 2.0], (len(t), 1)), atol=1e-12)
    # Kinetic + potential energy is conserved: E = m v^2/2 + I w^2/2 - m g.z.
    e0 = 0.5 * 2.0 * (0.25 + 16.0) + 0.5 * 3.0 * 4.0 + 2.0 * 9.81 * 3.0
    np.testing.assert_allclose(trajectory.energy, e0, rtol=1e-12)
    assert trajectory.body_names == ["box"]
    np.testing.assert_array_equal(trajectory.body_energy[:, 0], trajectory.energy)


def test_options_override_the_scene_like_the_flags(cli, tmp_path):
    status, out, err = cli("simulate", T_HANDLE, "--integrator", "splitting4", "--dt", "0.002",
                           "--duration", "0.5", "--json")
    assert status == 0, err
    expected = {k: v for k, v in json.loads(out).items() if k not in RUN_DEPENDENT}
    trajectory = tumble.simulate(T_HANDLE, integrator="splitting4", dt=0.002, duration=0.5)
    assert {k: v for k, v in trajectory.summary.items() if k not in RUN_DEPENDENT} == expected
    assert trajectory.summary["steps"] == 250


@pytest.mark.parametrize("flags, arguments", [
    (["--dt", "-1"], {"dt": -1.0}),
    (["--every", "0"], {"every": 0}),
    (["--integrator", "euler9"], {"integrator": "euler9"}),
    (["--dt", "1e-12", "--duration", "100"], {"dt": 1e-12, "duration": 100.0}),
])
def test_bad_options_raise_the_command_lines_message(cli, flags, arguments):
    status, _, err = cli("simulate", T_HANDLE, *flags)
    assert status == 1
    message = err.strip().splitlines()[-1].removeprefix("tumble simulate: error: ")
    with pytest.raises(tumble.InputError) as raised:
        tumble.simulate(str(T_HANDLE), **arguments)
    assert str(raised.value) == message


def test_a_bad_scene_file_names_the_file(tmp_path, cli):
    scene = tmp_path / "bad.json"
    scene.write_text('{"duration": 1, "dt": 2, "bodies": []}')
    status, _, err = cli("simulate", scene)
    assert status == 1
    with pytest.raises(tumble.InputError) as raised:
        tumble.simulate(str(scene))
    assert str(raised.value) == err.strip().removeprefix("tumble simulate: error: ")
    assert raised.value.file == str(scene)
    with pytest.raises(tumble.InputError, match="no such"):
        tumble.simulate(str(tmp_path / "missing.json"))


def test_a_bad_scene_dict_is_an_input_error():
    with pytest.raises(tumble.InputError, match="dt"):
        tumble.simulate(falling_box(dt=0.0))
    with pytest.raises(tumble.InputError, match="unknown|wobble"):
        tumble.simulate(falling_box(wobble=1))


def test_a_blow_up_is_reported_not_raised():
    # Explicit Euler on a fast spin about the unstable middle axis gains energy each step.
    scene = falling_box(integrator="explicit-euler", dt=0.05, duration=100.0, gravity=[0, 0, 0])
    scene["bodies"][0]["angular_velocity"] = [0.1, 20.0, 0.1]
    trajectory = tumble.simulate(scene)
    assert trajectory.blew_up
    assert trajectory.blow_up.startswith("blow-up: body 'box'")
    assert trajectory.summary["completed"] is False
    assert trajectory.t[-1] < 100.0
    assert np.all(np.isfinite(trajectory.position))


def test_integrators_are_the_command_lines_list(cli):
    status, out, err = cli("simulate", "--list-integrators", "--json")
    assert status == 0, err
    assert tumble.integrators() == json.loads(out)
    assert {"rk4", "splitting4"} <= {i["name"] for i in tumble.integrators()}


def test_ctrl_c_interrupts_a_long_simulate_within_a_second():
    script = textwrap.dedent("""
        import signal, sys, tumble
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
        scene = {"duration": 1e6, "dt": 1e-4, "integrator": "rk4",
                 "bodies": [{"inertia": {"principal": [1, 2, 3]}, "mass": 1,
                             "angular_velocity": [1, 2, 3]}]}
        print("running", flush=True)
        try:
            tumble.simulate(scene, every=1000000, allow_long=True)
        except KeyboardInterrupt:
            assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
            print("interrupted", flush=True)
            sys.exit(7)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, env=os.environ.copy())
    try:
        assert child.stdout.readline() == "running\n"
        time.sleep(0.5)  # inside the run
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=10)
        waited = time.monotonic() - sent
    finally:
        if child.poll() is None:
            child.kill()
    assert child.returncode == 7, err
    assert out == "interrupted\n" and err == ""
    assert waited < 2.0


def test_the_module_links_no_renderer():
    so = tumble._tumble.__file__
    linked = subprocess.run(["ldd", so], capture_output=True, text=True, check=True).stdout
    for library in ("libOSMesa", "libLLVM", "libSDL2", "libGL"):
        assert library not in linked


def test_simulate_releases_the_gil_while_it_runs():
    # The main thread keeps counting while another runs a simulation of about a second: were the
    # GIL held through the run, the main thread would stand still for all of it.
    import threading
    # The run's length is measured first, so that it lasts about a second on any machine.
    start = time.monotonic()
    tumble.simulate(falling_box(duration=100.0, dt=0.001, gravity=[0, 0, 0]), every=1000000)
    per_second = 100.0 / max(time.monotonic() - start, 1e-3)
    scene = falling_box(duration=max(300.0, per_second), dt=0.001, gravity=[0, 0, 0])
    done = {}

    def run():
        start = time.monotonic()
        done["trajectory"] = tumble.simulate(scene, every=10**10)
        done["seconds"] = time.monotonic() - start

    worker = threading.Thread(target=run)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.monotonic())
        sum(range(1000))
    worker.join()
    assert done["seconds"] > 0.2, "the run is too short to tell"
    largest_gap = max(b - a for a, b in zip(ticks, ticks[1:]))
    assert largest_gap < 0.5 * done["seconds"]
    assert len(done["trajectory"]) == 2
