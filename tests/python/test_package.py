"""The package as users meet it: every public name documented (help() says shapes and units),
type stubs beside the module naming exactly the public names, nothing printed on import, no
signal handler installed."""

import ast
import pathlib
import signal
import subprocess
import sys

import tumble


def stub_names():
    stub = pathlib.Path(tumble.__file__).with_name("__init__.pyi")
    tree = ast.parse(stub.read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
    return names


def test_the_stubs_name_every_public_name_and_only_those():
    assert pathlib.Path(tumble.__file__).with_name("py.typed").exists()
    assert stub_names() == set(tumble.__all__) | {"RunBlewUp"}
    for name in tumble.__all__:
        assert hasattr(tumble, name), name


def test_every_public_name_has_a_docstring_with_its_units():
    for name in tumble.__all__:
        doc = getattr(tumble, name).__doc__
        assert doc and len(doc) > 80, name
    assert "(N, B, 3)" in tumble.Trajectory.__doc__
    assert "(w, x, y, z)" in tumble.Trajectory.__doc__
    assert "COLUMNS" in tumble.MassProperties.__doc__
    assert "kg/m^3" in tumble.inspect.__doc__
    assert "kg/m^3" in tumble.inertials.__doc__


def test_import_prints_nothing_and_installs_no_signal_handler():
    script = ("import signal; before = signal.getsignal(signal.SIGINT); import tumble; "
              "assert signal.getsignal(signal.SIGINT) is before; "
              "assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout == "" and run.stderr == ""
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
