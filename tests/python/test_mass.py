"""tumble.inspect, mass_properties and primitive against closed forms and against the command
line's own output for the same input (`tumble inspect --json`, to the last digit)."""

import math
import pathlib

import numpy as np
import pytest

import tumble
from conftest import SOURCE, box_arrays, write_binary_stl, write_obj

ASSIMP_MODELS = pathlib.Path("/usr/share/assimp/models")


def box_inertia(mass, size):
    x, y, z = size
    return np.diag([mass / 12 * (y * y + z * z), mass / 12 * (x * x + z * z),
                    mass / 12 * (x * x + y * y)])


def test_a_box_from_numpy_arrays_has_the_closed_form_mass_properties():
    vertices, faces = box_arrays((1.0, 2.0, 3.0), origin=(0.5, -1.0, 2.0))
    box = tumble.mass_properties(vertices, faces, density=500.0)
    assert box.volume == pytest.approx(6.0, rel=1e-15)
    assert box.mass == pytest.approx(3000.0, rel=1e-15)
    assert box.density == 500.0
    np.testing.assert_allclose(box.center_of_mass, [1.0, 0.0, 3.5], rtol=0, atol=1e-14)
    np.testing.assert_allclose(box.inertia, box_inertia(3000.0, (1, 2, 3)), rtol=1e-14,
                               atol=1e-11)
    np.testing.assert_allclose(box.principal_moments,
                               sorted(np.diag(box_inertia(3000.0, (1, 2, 3)))), rtol=1e-14)
    assert box.method == "exact"
    assert box.warnings == []
    low, high = box.bounds
    np.testing.assert_array_equal(low, [0.5, -1.0, 2.0])
    np.testing.assert_array_equal(high, [1.5, 1.0, 5.0])


def test_principal_axes_are_columns_and_the_quaternion_is_wxyz():
    rotation = np.array([[0.36, 0.48, -0.8], [-0.8, 0.6, 0.0], [0.48, 0.64, 0.6]])
    vertices, faces = box_arrays((1.0, 2.0, 4.0), origin=(-0.5, -1.0, -2.0))
    turned = tumble.mass_properties(vertices @ rotation.T, faces)
    axes = turned.principal_axes
    moments = turned.principal_moments
    np.testing.assert_allclose(axes @ np.diag(moments) @ axes.T, turned.inertia, atol=1e-9)
    assert np.linalg.det(axes) == pytest.approx(1.0)
    # The largest moment belongs to the box's shortest edge, the rotated x axis.
    assert abs(axes[:, 2] @ rotation[:, 0]) == pytest.approx(1.0)
    w, x, y, z = turned.principal_quaternion
    from_quaternion = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    np.testing.assert_allclose(from_quaternion, axes, atol=1e-12)


def test_inertia_about_a_point_is_the_parallel_axis_theorem():
    vertices, faces = box_arrays((1.0, 1.0, 2.0))
    box = tumble.mass_properties(vertices, faces, mass=2.0)
    point = np.array([1.0, -2.0, 0.5])
    d = box.center_of_mass - point
    expected = box.inertia + 2.0 * (d @ d * np.eye(3) - np.outer(d, d))
    np.testing.assert_allclose(box.inertia_about(point), expected, rtol=1e-14)


@pytest.mark.parametrize("name", ["t_handle", "tennis_racket", "coin", "asteroid"])
def test_inspect_equals_the_command_lines_json(cli_json, name):
    mesh = SOURCE / "assets" / "meshes" / (name + ".obj")
    from_cli = cli_json("inspect", mesh)
    assert tumble.inspect(str(mesh)).to_dict() == dict(from_cli, method="exact")
    assert tumble.inspect(mesh).to_dict() == dict(from_cli, method="exact")  # a pathlib.Path


def test_options_mean_what_the_flags_mean(cli_json, tmp_path):
    vertices, faces = box_arrays((10.0, 20.0, 30.0))
    stl = tmp_path / "box_mm.stl"
    write_binary_stl(stl, vertices, faces)
    from_cli = cli_json("inspect", stl, "--mass", "2.5", "--scale", "0.001,0.002,0.001")
    ours = tumble.inspect(str(stl), mass=2.5, scale=(0.001, 0.002, 0.001))
    assert ours.to_dict() == dict(from_cli, method="exact")
    assert ours.volume == pytest.approx(0.01 * 0.04 * 0.03, rel=1e-12)


def test_a_real_model_nobody_here_wrote_reads_as_on_the_command_line(cli, cli_json):
    model = ASSIMP_MODELS / "OBJ" / "box.obj"
    if not model.exists():
        pytest.skip("assimp-testmodels is not installed")
    assert tumble.inspect(str(model)).to_dict() == dict(cli_json("inspect", model),
                                                        method="exact")


@pytest.mark.parametrize("fmt", ["urdf", "sdf", "mjcf"])
@pytest.mark.parametrize("frame", ["mesh", "principal"])
def test_to_xml_is_the_inertial_element_the_command_line_prints(cli, fmt, frame):
    mesh = SOURCE / "assets" / "meshes" / "t_handle.obj"
    status, out, err = cli("inspect", mesh, "--format", fmt, "--frame", frame)
    assert status == 0, err
    assert tumble.inspect(str(mesh)).to_xml(fmt, frame=frame) == out.rstrip("\n")


@pytest.mark.parametrize("kind, dims, volume, moments", [
    ("box", {"size": (1.0, 2.0, 3.0)}, 6.0, [13 / 12, 10 / 12, 5 / 12]),
    ("sphere", {"radius": 0.5}, 4 / 3 * math.pi / 8, [0.1] * 3),
    ("cylinder", {"radius": 1.0, "length": 2.0}, 2 * math.pi, [7 / 12, 7 / 12, 0.5]),
    ("cone", {"radius": 1.0, "height": 2.0}, 2 * math.pi / 3,
     [3 / 20 * (1 + 4 / 4), 3 / 20 * (1 + 4 / 4), 0.3]),
])
def test_primitives_have_their_closed_forms(kind, dims, volume, moments):
    solid = tumble.primitive(kind, density=1000.0, **dims)
    assert solid.volume == pytest.approx(volume, rel=1e-14)
    assert solid.mass == pytest.approx(1000.0 * volume, rel=1e-14)
    np.testing.assert_allclose(np.diag(solid.inertia) / solid.mass, moments, rtol=1e-13)
    assert solid.method == "closed form"
    by_mass = tumble.primitive(kind, mass=3.0, **dims)
    assert by_mass.mass == 3.0


def test_a_primitive_agrees_with_a_fine_mesh_of_it():
    # A finely tessellated cylinder converges to the closed form at O(1/n^2).
    errors = []
    for n in (64, 128):
        angles = np.linspace(0, 2 * math.pi, n, endpoint=False)
        ring = np.stack([np.cos(angles), np.sin(angles)], axis=1)
        vertices = np.vstack([np.c_[ring, -np.ones(n)], np.c_[ring, np.ones(n)],
                              [[0, 0, -1], [0, 0, 1]]])
        faces = []
        for i in range(n):
            j = (i + 1) % n
            faces += [(i, j, n + j), (i, n + j, n + i), (2 * n, j, i), (2 * n + 1, n + i, n + j)]
        mesh = tumble.mass_properties(vertices, np.array(faces))
        exact = tumble.primitive("cylinder", radius=1.0, length=2.0)
        errors.append(abs(mesh.inertia[0, 0] / mesh.mass - exact.inertia[0, 0] / exact.mass))
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.02)


@pytest.mark.parametrize("vertices, faces, message", [
    (np.zeros((4, 2)), [[0, 1, 2]], "vertices: expected an array of shape (N, 3)"),
    (np.zeros((4, 3)), [[0, 1]], "faces: expected an array of shape (M, 3)"),
    (np.zeros((4, 3)), np.array([[0.0, 1.0, 2.0]]), "faces: expected integer vertex indices"),
    ([[0, 0, 0], [1, 0, 0], [0, float("nan"), 0]], [[0, 1, 2]], "vertices[2]: not a finite point"),
    (np.eye(3), [[0, 1, 3]], "faces[0]: vertex index 3 out of range (3 vertices"),
    (np.eye(3), [[0, -1, 2]], "faces[0]: vertex index -1 out of range"),
    (np.eye(3), np.zeros((0, 3), dtype=int), "faces: no triangles"),
])
def test_bad_arrays_are_input_errors_never_crashes(vertices, faces, message):
    with pytest.raises(tumble.InputError) as error:
        tumble.mass_properties(vertices, faces)
    assert message in str(error.value)
    assert error.value.file is None
    assert isinstance(error.value, ValueError)


def test_an_open_mesh_is_refused_with_the_checks_of_a_file():
    vertices, faces = box_arrays()
    with pytest.raises(tumble.InputError, match="mesh arrays: .*not closed|mesh arrays: .*open"):
        tumble.mass_properties(vertices, faces[:-1])


def test_errors_name_the_file_and_carry_it(tmp_path):
    missing = tmp_path / "missing.stl"
    with pytest.raises(tumble.InputError) as error:
        tumble.inspect(str(missing))
    assert str(error.value) == str(missing) + ": no such file"
    assert error.value.file == str(missing)
    with pytest.raises(tumble.InputError, match="give either a density or a mass"):
        tumble.inspect(str(missing), density=1.0, mass=1.0)
    with pytest.raises(tumble.InputError, match="scale: expected three numbers"):
        tumble.mass_properties(*box_arrays(), scale=(1.0, 2.0))
    with pytest.raises(tumble.InputError, match="kind: expected box, sphere"):
        tumble.primitive("torus", radius=1.0)
    with pytest.raises(tumble.InputError, match="cylinder: missing dimension 'length'"):
        tumble.primitive("cylinder", radius=1.0)
    with pytest.raises(tumble.InputError, match="sphere radius"):
        tumble.primitive("sphere", radius=-1.0)


def test_warnings_are_returned_not_printed(capfd):
    vertices, faces = box_arrays()
    twice = tumble.mass_properties(np.vstack([vertices, vertices + [0.5, 0, 0]]),
                                   np.vstack([faces, faces + 8]), allow_overlap=True)
    assert twice.warnings, "overlapping parts must come with a warning"
    assert any("twice" in w for w in twice.warnings)
    assert twice.to_dict()["warnings"] == twice.warnings
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_shell_mode_is_named_and_equals_the_command_line(cli_json, tmp_path):
    vertices, faces = box_arrays((1.0, 1.0, 1.0))
    obj = tmp_path / "cube.obj"
    write_obj(obj, vertices, faces)
    shell = tumble.inspect(str(obj), shell=0.01, inertia="shell")
    assert shell.method == "shell"
    assert shell.to_dict() == dict(cli_json("inspect", obj, "--shell", "0.01"), method="shell")
    assert shell.volume == pytest.approx(6 * 0.01, rel=1e-12)


def test_overlap_keyword_takes_the_union_the_sum_or_refuses():
    # Two unit cubes, the second moved by 0.5 along x: they share 0.5 m^3.
    vertices, faces = box_arrays((1.0, 1.0, 1.0))
    both = (np.vstack([vertices, vertices + [0.5, 0, 0]]), np.vstack([faces, faces + 8]))
    united = tumble.mass_properties(*both)
    assert united.volume == pytest.approx(1.5, rel=1e-12)
    assert united.to_dict()["overlap"] == "union"
    assert united.to_dict()["shared_volume"] == pytest.approx(0.5, rel=1e-12)
    assert any("shared volume, counted once, is 0.5 m^3" in w for w in united.warnings)
    summed = tumble.mass_properties(*both, overlap="sum")
    assert summed.volume == pytest.approx(2.0, rel=1e-12)
    assert summed.to_dict()["overlap"] == "sum"
    with pytest.raises(tumble.InputError, match="parts 1 and 2 of 2 overlap"):
        tumble.mass_properties(*both, overlap="refuse")
    with pytest.raises(tumble.InputError, match="overlap: expected 'union', 'sum' or 'refuse'"):
        tumble.mass_properties(*both, overlap="merge")
    with pytest.raises(tumble.InputError, match="allow_overlap: True is overlap='sum'"):
        tumble.mass_properties(*both, overlap="refuse", allow_overlap=True)


def test_convex_and_auto_name_the_hull_and_equal_the_command_line(cli_json, tmp_path):
    vertices, faces = box_arrays((1.0, 2.0, 3.0))
    open_faces = faces[2:]  # one face of the box (two triangles) removed: exact refuses it
    with pytest.raises(tumble.InputError, match="the surface is open"):
        tumble.mass_properties(vertices, open_faces)
    hull = tumble.mass_properties(vertices, open_faces, density=2.0, inertia="convex")
    assert hull.method == "convex"
    assert hull.mass == pytest.approx(2.0 * 6.0, rel=1e-12)  # the whole box's volume
    fallback = tumble.mass_properties(vertices, open_faces, density=2.0, inertia="auto")
    assert fallback.method == "convex"
    assert any("exact inertia refused" in w for w in fallback.warnings)
    obj = tmp_path / "cube.obj"
    write_obj(obj, vertices, faces)
    convex = tumble.inspect(obj, inertia="convex")
    assert convex.to_dict() == cli_json("inspect", obj, "--inertia", "convex")
    legacy = tumble.inspect(obj, inertia="legacy")
    assert legacy.method == "legacy"
    assert legacy.to_dict() == cli_json("inspect", obj, "--inertia", "legacy")
    with pytest.raises(
        tumble.InputError, match="expected 'exact', 'convex', 'shell', 'legacy' or 'auto'"
    ):
        tumble.inspect(obj, inertia="nonsense")
