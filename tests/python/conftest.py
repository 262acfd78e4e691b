"""What the tests of the Python module share: the `tumble` executable the module is compared
with (the command line is the oracle for every call's numbers), the source tree, and meshes
written from numpy arrays."""

import json
import os
import pathlib
import struct
import subprocess

import numpy as np
import pytest

import tumble

SOURCE = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    """Runs `tumble ARGS...` and returns (status, stdout, stderr)."""
    executable = tumble.executable()

    def run(*args, cwd=None):
        done = subprocess.run([executable, *map(os.fspath, args)], capture_output=True,
                              text=True, cwd=cwd, stdin=subprocess.DEVNULL)
        return done.returncode, done.stdout, done.stderr

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    """`tumble ARGS... --json`'s document, parsed; fails the test on a non-zero status."""

    def run(*args):
        status, out, err = cli(*args, "--json")
        assert status == 0, err
        return json.loads(out)

    return run


def box_arrays(size=(1.0, 2.0, 3.0), origin=(0.0, 0.0, 0.0)):
    """A closed, outward-wound box: vertices (8, 3) and faces (12, 3)."""
    x, y, z = size
    corners = np.array([[i * x, j * y, k * z] for k in (0, 1) for j in (0, 1) for i in (0, 1)],
                       dtype=float) + np.asarray(origin, dtype=float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    faces = []
    for a, b, c, d in quads:
        faces += [(a, b, c), (a, c, d)]
    return corners, np.array(faces, dtype=np.int64)


def write_binary_stl(path, vertices, faces):
    """A binary STL of the triangles (normals left zero, as readers may)."""
    with open(path, "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(faces)))
        for face in faces:
            out.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for v in face:
                out.write(struct.pack("<3f", *vertices[v]))
            out.write(b"\0\0")


def write_obj(path, vertices, faces):
    with open(path, "w") as out:
        for v in vertices:
            out.write("v %r %r %r\n" % tuple(float(c) for c in v))
        for f in faces:
            out.write("f %d %d %d\n" % tuple(int(i) + 1 for i in f))
