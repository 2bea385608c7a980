"""`pyramid-sim scene --out x.xml` writes an MJCF that opens anywhere: its meshes beside it."""

import re
import shutil

import mujoco
import pytest

from pyramid_sim.cli import main
from pyramid_sim.config import SimConfig
from pyramid_sim.physics.scene import build_scene

pytestmark = pytest.mark.physics


@pytest.mark.parametrize("robot", ["panda", "baxter", "so101"])  # each robot's scene
def test_the_xml_and_its_meshes_open_after_a_move(tmp_path, capsys, robot):
    out = tmp_path / "made" / "x.xml"
    assert (
        main(
            [
                "scene",
                "--structure",
                "pyramid",
                "--layers",
                "1",
                "--robot",
                robot,
                "--out",
                str(out),
            ]
        )
        == 0
    )
    line = capsys.readouterr().out.strip()
    assert line.endswith(
        f"-> {out}, {tmp_path / 'made' / 'x_meshes'}/ "
        f"({len(list((tmp_path / 'made' / 'x_meshes').iterdir()))} mesh files)"
    )
    files = re.findall(r'file="([^"]*)"', out.read_text())
    assert files and all(f.startswith("x_meshes/") for f in files)  # nothing absolute
    moved = tmp_path / "elsewhere"
    moved.mkdir()
    shutil.move(str(out), moved / "x.xml")
    shutil.move(str(tmp_path / "made" / "x_meshes"), moved / "x_meshes")
    loaded = mujoco.MjModel.from_xml_path(str(moved / "x.xml"))
    config = SimConfig.for_robot(robot)
    compiled = build_scene(config, 1 + config.spare_bricks).model
    assert (loaded.nbody, loaded.ngeom, loaded.nmesh) == (
        compiled.nbody,
        compiled.ngeom,
        compiled.nmesh,
    )
    assert loaded.nmesh > 0
