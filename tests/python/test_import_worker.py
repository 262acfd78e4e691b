"""The import worker inside Python: meshes assimp reads (OBJ, PLY, ...) are read by tumble-import,
a program of its own started for the purpose, never a fork of the interpreter."""

import os
import pathlib
import subprocess
import sys
import textwrap
import threading

import pytest

import tumble
from conftest import box_arrays, write_obj


def children_of(pid):
    """Process ids whose parent is `pid` (from /proc)."""
    found = []
    for entry in pathlib.Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        if int(fields[1]) == pid:
            found.append(int(entry.name))
    return found


def test_the_worker_is_tumble_import_not_a_copy_of_the_interpreter(tmp_path):
    obj = tmp_path / "box.obj"
    write_obj(obj, *box_arrays())
    # A thread of the interpreter holds a lock while the worker starts: a fork would copy the
    # interpreter, lock and all.
    holding = threading.Lock()
    holding.acquire()
    try:
        assert tumble.inspect(str(obj)).volume == pytest.approx(6.0)
    finally:
        holding.release()
    workers = [pid for pid in children_of(os.getpid())
               if os.readlink("/proc/%d/exe" % pid).endswith("/tumble-import")]
    assert len(workers) == 1
    assert os.readlink("/proc/%d/exe" % workers[0]) != os.readlink("/proc/self/exe")


def test_output_is_not_duplicated_and_exit_handlers_run_once(tmp_path):
    # If the worker were a fork of this interpreter, what Python holds buffered and its exit
    # handlers would be in it too: the line below would be printed twice, or the run hang.
    obj = tmp_path / "box.obj"
    write_obj(obj, *box_arrays())
    script = textwrap.dedent("""
        import atexit, sys, tumble
        atexit.register(lambda: print("exit handler"))
        sys.stdout.write("buffered before the import\\n")
        print(tumble.inspect(sys.argv[1]).volume)
    """)
    run = subprocess.run([sys.executable, "-c", script, str(obj)], capture_output=True,
                         text=True, timeout=60, env=dict(os.environ, PYTHONUNBUFFERED=""))
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == ["buffered before the import", "6.0", "exit handler"]
    assert run.stderr == ""


def test_assimps_crash_on_a_file_is_an_input_error_and_python_lives_on(tmp_path):
    source = pathlib.Path(__file__).resolve().parents[1] / "fuzz" / "corpus" / "mesh_import"
    crash = source / "regression_assimp_off_segv"
    if not crash.exists():
        pytest.skip("the fuzz corpus is not beside the tests")
    off = tmp_path / "crash.off"
    off.write_bytes(crash.read_bytes()[1:])  # the corpus's first byte picks the extension
    with pytest.raises(tumble.InputError, match="assimp crashed reading it"):
        tumble.inspect(str(off))
    obj = tmp_path / "box.obj"
    write_obj(obj, *box_arrays())
    assert tumble.inspect(str(obj)).mass == pytest.approx(6000.0)
