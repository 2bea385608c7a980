"""At rest the pads hold a brick up to Coulomb's limit 2 mu F / g and no further: the contact
settings of the grip (pads' friction, condim, stiffness; the scene's elliptic cones and
impratio) measured on a brick squeezed between two pads, nothing else moving."""

import mujoco
import pytest

from pyramid_sim.config import GripperConfig, SimConfig
from pyramid_sim.physics.robot_models.common import tune_pads
from pyramid_sim.physics.scene import brick_spec
from pyramid_sim.resources import ASSETS

GRAVITY = 9.81


def _drop_mm(mass: float, force: float, pad_friction: float) -> float:
    """How far (mm) a brick of `mass`, squeezed by two pads with `force` each, sinks in 1 s."""
    config = SimConfig()
    spec = mujoco.MjSpec.from_file(str(ASSETS / "scene.xml"))  # the scene's solver options
    grip = GripperConfig(force=force, pad_friction=pad_friction)
    brick = brick_spec(config)
    brick.geom("geom").mass = mass
    frame = spec.worldbody.add_frame(pos=[0.0, 0.0, 1.0])
    spec.attach(brick, prefix="held/", frame=frame)
    pads = []
    half = config.brick.width / 2
    for side in (1, -1):
        body = spec.worldbody.add_body(name=f"pad{side}", pos=[0.0, side * (half + 0.006), 1.0])
        body.add_joint(name=f"slide{side}", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0, -side, 0])
        pads.append(
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.02, 0.005, 0.02], mass=0.02)
        )
        act = spec.add_actuator(
            name=f"press{side}", target=f"slide{side}", trntype=mujoco.mjtTrn.mjTRN_JOINT
        )
        act.set_to_position(kp=grip.stiffness, kv=40.0)
        act.forcerange = [-force, force]
        act.forcelimited = True
    tune_pads(spec, pads, grip)
    model = spec.compile()
    data = mujoco.MjData(model)
    data.ctrl[:] = 0.02  # 9 mm past the brick's face: the force limit sets the squeeze
    z = model.joint("held/joint").qposadr[0] + 2
    brick_body = model.body("held/brick").id
    for _ in range(int(0.3 / model.opt.timestep)):  # squeeze, the brick held in place
        data.qpos[z], data.qvel[model.body_dofadr[brick_body] + 2] = 1.0, 0.0
        mujoco.mj_step(model, data)
    start = data.qpos[z]
    for _ in range(int(1.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    return float((start - data.qpos[z]) * 1000.0)


@pytest.mark.parametrize("force, pad_friction", [(10.0, 1.0), (20.0, 0.6)])
def test_a_brick_held_still_slips_out_at_the_coulomb_limit(force, pad_friction):
    limit = 2 * pad_friction * force / GRAVITY  # kg
    assert _drop_mm(0.85 * limit, force, pad_friction) < 1.0
    assert _drop_mm(1.15 * limit, force, pad_friction) > 10.0
