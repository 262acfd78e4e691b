"""tumble.inertials and RobotInertials against `tumble inertials` on the same robot files: the
JSON to the last digit, the links --check fails, and the rewritten file byte for byte."""

import json
import shutil

import numpy as np
import pytest

import tumble
from conftest import SOURCE, box_arrays, write_binary_stl

ARM = SOURCE / "assets" / "robots" / "arm"
PACKAGES = {"tumble_assets": str(SOURCE / "assets")}
PACKAGE_FLAG = ("--package-path", "tumble_assets=" + str(SOURCE / "assets"))


@pytest.mark.parametrize("name", ["arm.urdf", "arm.sdf", "arm.xml"])
def test_the_report_is_the_command_lines_json(cli, name):
    status, out, err = cli("inertials", *PACKAGE_FLAG, ARM / name, "--json")
    assert status == 0, err
    report = tumble.inertials(ARM / name, package_paths=PACKAGES)
    assert report.to_dict() == json.loads(out)
    assert report.links == json.loads(out)["links"]
    assert report.errors == []
    assert report.file == str(ARM / name)


def test_failing_is_what_check_fails(cli):
    status, out, _ = cli("inertials", *PACKAGE_FLAG, ARM / "arm.urdf", "--json", "--check",
                         "--tolerance", "0.02")
    assert status == 4
    report = tumble.inertials(str(ARM / "arm.urdf"), package_paths=PACKAGES)
    assert report.to_dict(tolerance=0.02) == json.loads(out)
    assert report.failing() == ["turret", "upper_arm", "hand"]
    # The upper arm's moments differ by 0.0162, its centre of mass by 1.69 link sizes.
    assert "upper_arm" in report.failing(tolerance=1.0)
    assert report.failing(tolerance=1e9) == ["hand"]  # its stated tensor is impossible


def test_options_mean_what_the_flags_mean(cli):
    status, out, err = cli("inertials", *PACKAGE_FLAG, ARM / "arm.urdf", "--json", "--from",
                           "visual", "--density", "2700")
    assert status == 0, err
    report = tumble.inertials(ARM / "arm.urdf", geometry="visual", density=2700.0,
                              package_paths=PACKAGES)
    assert report.to_dict() == json.loads(out)
    assert report.geometry == "visual" and report.format == "urdf"


@pytest.mark.parametrize("frame", ["mesh", "principal"])
def test_write_is_the_command_lines_output_byte_for_byte(cli, tmp_path, frame):
    by_cli = tmp_path / "cli.urdf"
    status, _, err = cli("inertials", *PACKAGE_FLAG, ARM / "arm.urdf", "--frame", frame, "-o",
                         by_cli)
    assert status == 0, err
    ours = tmp_path / "python.urdf"
    report = tumble.inertials(ARM / "arm.urdf", package_paths=PACKAGES)
    assert report.write(ours, frame=frame) == str(ours)
    assert ours.read_bytes() == by_cli.read_bytes()
    # Copied beside the meshes' relative paths, the rewritten file passes the check.
    fixed = ARM.parent / ("_python_fixed_%s.urdf" % frame)
    try:
        shutil.copy(ours, ARM / fixed.name)
        again = tumble.inertials(ARM / fixed.name, package_paths=PACKAGES)
        assert again.failing() == []
    finally:
        (ARM / fixed.name).unlink(missing_ok=True)


def test_the_computed_box_link_is_the_closed_form():
    report = tumble.inertials(ARM / "arm.urdf", package_paths=PACKAGES)
    upper = next(link for link in report.links if link["name"] == "upper_arm")
    computed = upper["computed"]
    assert computed["mass"] == pytest.approx(1.2)
    np.testing.assert_allclose(computed["center_of_mass"], [0.0, 0.0, 0.15], atol=1e-15)


def test_bad_input_raises_the_command_lines_message(cli, tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'>")
    status, _, err = cli("inertials", bad)
    assert status == 1
    with pytest.raises(tumble.InputError) as raised:
        tumble.inertials(bad)
    assert err.strip() == "tumble inertials: error: " + str(raised.value)
    assert raised.value.file == str(bad)
    # A package path the file needs and was not given: the command's message.
    status, _, err = cli("inertials", ARM / "arm.urdf")
    assert status == 1
    with pytest.raises(tumble.InputError) as raised:
        tumble.inertials(ARM / "arm.urdf")
    assert err.strip() == "tumble inertials: error: " + str(raised.value)
    assert "package 'tumble_assets' is not known" in str(raised.value)
    with pytest.raises(tumble.InputError, match="geometry: expected collision or visual"):
        tumble.inertials(ARM / "arm.urdf", geometry="both")
    with pytest.raises(tumble.InputError, match="frame: expected mesh or principal"):
        tumble.inertials(ARM / "arm.urdf", package_paths=PACKAGES).write(
            tmp_path / "x.urdf", frame="world")


def test_a_failed_link_is_reported_and_blocks_writing(cli, tmp_path):
    # A link whose mesh is open (a box missing a face) fails; the others are still computed.
    vertices, faces = box_arrays((0.1, 0.2, 0.3))
    write_binary_stl(tmp_path / "open.stl", vertices, faces[:-1])
    write_binary_stl(tmp_path / "closed.stl", vertices, faces)
    robot = tmp_path / "two.urdf"
    robot.write_text("""<robot name="two">
  <link name="good"><collision><geometry><mesh filename="closed.stl"/></geometry></collision></link>
  <link name="bad"><collision><geometry><mesh filename="open.stl"/></geometry></collision></link>
</robot>
""")
    status, out, err = cli("inertials", robot, "--json")
    assert status == 1
    report = tumble.inertials(robot)
    assert report.to_dict() == json.loads(out)
    assert len(report.errors) == 1 and "link 'bad'" in report.errors[0]
    assert "tumble inertials: error: " + report.errors[0] in err
    assert report.links[0]["computed"]["mass"] == pytest.approx(6.0)  # 0.006 m^3 of water
    with pytest.raises(tumble.InputError, match="nothing written"):
        report.write(tmp_path / "out.urdf")
    assert not (tmp_path / "out.urdf").exists()


def test_weighed_masses_are_the_command_lines(cli):
    status, out, err = cli("inertials", *PACKAGE_FLAG, ARM / "arm.urdf", "--json", "--mass",
                           "hand=0.5", "--density", "turret=2000", "--total-mass", "10")
    assert status == 0, err
    report = tumble.inertials(ARM / "arm.urdf", package_paths=PACKAGES, masses={"hand": 0.5},
                              densities={"turret": 2000}, total_mass=10)
    assert report.to_dict() == json.loads(out)
    assert report.total == json.loads(out)["total"]
    assert report.total["mass"] == pytest.approx(10, rel=1e-12)
    hand = next(link for link in report.links if link["name"] == "hand")
    assert hand["computed"]["mass"] == 0.5 and hand["computed"]["mass_from"] == "--mass"
    with pytest.raises(tumble.InputError, match="--mass 'nope=1': no link 'nope'"):
        tumble.inertials(ARM / "arm.urdf", package_paths=PACKAGES, masses={"nope": 1})
