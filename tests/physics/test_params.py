"""Every row of the parameter table reaches the compiled model, read back from MuJoCo."""

import mujoco
import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.params import PARAMS
from pyramid_sim.physics import names as c
from pyramid_sim.physics.scene import build_scene
from pyramid_sim.robots.panda import PANDA

# How each parameter is read back from a compiled model: adding a row to the table without a
# reader here fails test_every_parameter_has_a_reader.
READERS = {
    "friction": lambda m: m.geom(c.brick_name(0) + "geom").friction[0],
    "brick_mass": lambda m: m.body(c.brick_name(0) + "brick").mass[0],
    "grip_force": lambda m: m.actuator(PANDA.arms["left"].gripper_actuator).forcerange[1],
    "pad_friction": lambda m: m.geom(PANDA.arms["right"].pads[0]).friction[0],
}


def test_every_parameter_has_a_reader():
    assert set(READERS) == {p.name for p in PARAMS}


@pytest.mark.parametrize("param", PARAMS, ids=lambda p: p.name)
def test_every_parameter_reaches_the_model(param):
    value = round(param.low + 0.37 * (param.high - param.low), 3)
    assert value != param.default
    model: mujoco.MjModel = build_scene(param.apply(SimConfig(), value), 1).model
    assert READERS[param.name](model) == pytest.approx(value)
    assert READERS[param.name](build_scene(SimConfig(), 1).model) == pytest.approx(param.default)
