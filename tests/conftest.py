"""Shared fixtures. Nothing here imports MuJoCo at collection time, so the pure tests
(`pytest -m "not physics"`) run where MuJoCo cannot be imported; with
PYRAMID_SIM_BLOCK_MUJOCO=1 it is made unimportable, to prove it."""

import os
import sys

import pytest

collect_ignore: list[str] = []
if os.environ.get("PYRAMID_SIM_BLOCK_MUJOCO") == "1":
    sys.modules["mujoco"] = None  # type: ignore[assignment]  # `import mujoco` now raises
    collect_ignore.append("physics")  # they import MuJoCo to be collected, and are all physics

_BUILDS: dict = {}


@pytest.fixture(scope="session", autouse=True)
def _matplotlib_config_in_a_temporary_folder(tmp_path_factory):
    """matplotlib makes ~/.config/matplotlib when first imported: the tests, and the commands
    they run, use a folder of pytest's instead, so HOME keeps nothing of theirs."""
    os.environ["MPLCONFIGDIR"] = str(tmp_path_factory.mktemp("matplotlib"))
    yield


def build_once(structure: str, layers: int):
    """Each default build is simulated once per session and shared by the tests that read it."""
    from pyramid_sim.config import SimConfig
    from pyramid_sim.core.structures import StructureSpec
    from pyramid_sim.jobs.build import run_build
    from pyramid_sim.physics.reach import prepare

    key = (structure, layers)
    if key not in _BUILDS:
        config = SimConfig()
        _BUILDS[key] = run_build(prepare(StructureSpec(structure, layers=layers), config), config)
    return _BUILDS[key]


@pytest.fixture(scope="session")
def built():
    return build_once


@pytest.fixture
def refused(capsys):
    """Run the command line expecting a refusal: exit status 2 and one error line without a
    traceback, which it returns."""
    from pyramid_sim.cli import main

    def run(argv: list[str]) -> str:
        try:
            code = main(argv)
        except SystemExit as exit_info:  # argparse's own refusals
            code = exit_info.code
        err = capsys.readouterr().err
        assert code == 2, err
        assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
        return err

    return run


@pytest.fixture
def teleport():
    """Move a brick (by magazine slot) of a running BuildLoop to a position, at rest: how tests
    knock a brick out of a hand or off the structure."""
    from pyramid_sim.core.poses import yaw_quaternion

    def move(loop, data, slot: int, position: tuple[float, float, float], yaw=None) -> None:
        """`yaw`: lying flat, turned so; None keeps the brick's orientation."""
        loop.handles.place_brick(data, slot, position, None if yaw is None else yaw_quaternion(yaw))

    return move


def measured_on_target(plan, **changes):
    """What the loop would measure of a clean build of `plan`: every brick at rest on its
    target, nothing past a limit; `changes` replace fields (as a fault would)."""
    from dataclasses import replace

    import numpy as np

    from pyramid_sim.core.measurements import Measurements
    from pyramid_sim.core.poses import yaw_quaternion

    poses = [b.target.pose for b in plan.bricks]
    clean = Measurements(
        plan=plan,
        slot_of={b.index: i for i, b in enumerate(plan.bricks)},
        final_pos=np.array([p.position for p in poses]),
        final_quat=np.array([yaw_quaternion(p.yaw) for p in poses]),
        slip_mm={b.index: 1.0 for b in plan.bricks},
        drops=(),
        knocks=(),
        sim_time=12.0,
        wall_time=1.0,
        arm_arm_contacts=0,
        arm_body_contacts=0,
        zone_violations=0,
        finger_limit_mm=0.0,
        joint_speed_ratio=0.5,
        joint_torque_ratio=0.5,
        torque_joint=3,
        speed_joint=0,
        warnings={},
        failure=None,
        idle_motion_mm=0.0,
        contact_friction={"brick_brick": 1.0, "brick_table": 1.0, "pad_brick": 1.0},
        closest_arm_m=0.1,
        closest_arm_time=1.0,
        physics_steps=6000,
        ik_solves=1000,
    )
    return replace(clean, **changes)


@pytest.fixture
def on_target():
    """`measured_on_target`, for tests of the judge."""
    return measured_on_target


@pytest.fixture
def fake_build(monkeypatch):
    """Stand in for the physics behind `build` (the reach check and jobs.build), so the command
    line's own work (verdict, files, locks, progress) is tested in a fraction of a second with
    MuJoCo blocked. Every brick lands on its target; set `changes` to alter what was measured
    (as tests/test_judge.py does), `frames` for the frames filmed a brick (and as many after the
    last, as the scene settles), `during(i)` to act before brick i is reported placed."""
    import types

    from pyramid_sim.core.plan import make_plan
    from pyramid_sim.output.judge import judge

    fake = types.SimpleNamespace(changes={}, frames=0, during=None)

    def prepare(spec, config, arms="both"):
        return make_plan(spec, config, arms)

    def run_build(
        plan, config, *, on_placed=None, video=None, on_frame=None, snapshot=None, replay=None
    ):  # no replay.npz: the poses are the physics'
        filmed = 0

        def film() -> None:  # the frames of one brick's work, or of the settling at the end
            nonlocal filmed
            for _ in range(fake.frames if video is not None else 0):
                filmed += 1
                if on_frame is not None:
                    on_frame(filmed)

        for i in range(len(plan.bricks)):
            film()
            if fake.during is not None:
                fake.during(i)
            if on_placed is not None:
                on_placed(i + 1)
        film()
        return judge(measured_on_target(plan, **fake.changes), config)

    reach = types.ModuleType("pyramid_sim.physics.reach")
    reach.prepare = prepare
    jobs = types.ModuleType("pyramid_sim.jobs.build")
    jobs.run_build = run_build
    monkeypatch.setitem(sys.modules, "pyramid_sim.physics.reach", reach)
    monkeypatch.setitem(sys.modules, "pyramid_sim.jobs.build", jobs)
    monkeypatch.setenv("MUJOCO_GL", "egl")  # a --video run chooses no backend of its own
    return fake


def write_checkpoint(
    folder, *, action=12, state=16, dataset=None, env=None, train=True, output_dir=None
):
    """A lerobot checkpoint's files as `checkpoint_inputs` reads them, weightless: config.json
    (its features' widths), and train_config.json naming `dataset` (a folder written by
    `write_recording`, or any path) and holding `env` (the plugin's fields), unless not
    `train`. Returns the folder, as text."""
    import json

    folder.mkdir(parents=True)
    features = {"observation.state": {"type": "STATE", "shape": [state]}}
    config = {"type": "act", "input_features": features,
              "output_features": {"action": {"type": "ACTION", "shape": [action]}}}  # fmt: skip
    (folder / "config.json").write_text(json.dumps(config))
    if train:
        doc = {"dataset": {"repo_id": "local/demos", "root": None if dataset is None
                           else str(dataset)},
               "env": None if env is None else {"type": "pyramid_sim", **env},
               "output_dir": str(output_dir or folder.parent)}  # fmt: skip
        (folder / "train_config.json").write_text(json.dumps(doc))
    return str(folder)


def write_recording(root, *, robot_type="panda_bimanual", fps=10, **doc):
    """The metadata a `pyramid-sim record` dataset keeps of itself: meta/info.json (lerobot's
    fps and robot_type) and meta/pyramid_sim/dataset.json (`doc` over a 2-brick anchored
    recording's)."""
    import json

    (root / "meta" / "pyramid_sim").mkdir(parents=True)
    (root / "meta" / "info.json").write_text(json.dumps({"fps": fps, "robot_type": robot_type}))
    ours = {"structure": "pyramid-even", "size": {"layers": 1}, "variation": "layout",
            "action_mode": "anchored", **doc}  # fmt: skip
    (root / "meta" / "pyramid_sim" / "dataset.json").write_text(json.dumps(ours))
    return root


@pytest.fixture
def checkpoint():
    """`write_checkpoint`, for the tests of what a checkpoint was trained on."""
    return write_checkpoint


@pytest.fixture
def recording():
    """`write_recording`."""
    return write_recording
