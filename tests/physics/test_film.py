"""What the cameras film: the robots drawn with their visual meshes and never their collision
geometry, a spawn marker that lines up with the brick, a lab with no black in any frame, and a
magazine of spare bricks out of every camera's sight, at rest until a brick is spawned."""

import itertools
import os

os.environ.setdefault("MUJOCO_GL", "egl")  # before MuJoCo's first import in this process

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from pyramid_sim.config import SimConfig  # noqa: E402
from pyramid_sim.core.poses import yaw_of  # noqa: E402
from pyramid_sim.core.structures import StructureSpec  # noqa: E402
from pyramid_sim.output.renderer import HeadlessRenderer  # noqa: E402
from pyramid_sim.physics.clearance import subtree  # noqa: E402
from pyramid_sim.physics.hooks import BuildHooks  # noqa: E402
from pyramid_sim.physics.loop import BuildLoop  # noqa: E402
from pyramid_sim.physics.reach import prepare  # noqa: E402
from pyramid_sim.physics.scene import build_scene  # noqa: E402

CAMERAS = ("overview", "front", "top")


def _loop(robot: str = "panda") -> BuildLoop:
    config = SimConfig(robot=robot)
    return BuildLoop.of(prepare(StructureSpec("pyramid-even", layers=1), config), config)


def _robot_geoms(model: mujoco.MjModel, config: SimConfig) -> list[int]:
    robot = config.robot_description
    roots = [robot.arms[a].root_body for a in robot.arms] + list(robot.static_bodies)
    bodies = set().union(*(subtree(model, r) for r in roots))
    return [g for g in range(model.ngeom) if model.geom_bodyid[g] in bodies]


@pytest.mark.parametrize("robot", ["panda", "baxter"])
def test_no_collision_geometry_of_the_robot_is_drawn(robot):
    config = SimConfig(robot=robot)
    model = build_scene(config, 2).model
    shown = mujoco.MjvOption().geomgroup  # what a default renderer draws
    geoms = _robot_geoms(model, config)
    colliding = [g for g in geoms if model.geom_contype[g] or model.geom_conaffinity[g]]
    drawn = [g for g in geoms if shown[model.geom_group[g]] and model.geom_rgba[g, 3] > 0]
    assert colliding and drawn
    assert not set(colliding) & set(drawn), [
        model.geom(g).name for g in set(colliding) & set(drawn)
    ]
    if robot == "panda":  # its visual meshes, in the colours of the real arm
        colours = {tuple(np.round(model.geom_rgba[g], 2)) for g in drawn}
        assert len(colours) >= 4 and all(
            model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH for g in drawn
        )


def test_the_visual_meshes_weigh_nothing():
    """Every link keeps the URDF's own mass: drawing meshes adds none."""
    import xml.etree.ElementTree as ET

    from pyramid_sim.physics.robot_models.common import robots_dir

    model = build_scene(SimConfig(), 2).model
    drawn = [g for g in range(model.ngeom) if model.geom_group[g] == 2]
    assert drawn and all(model.geom_contype[g] == model.geom_conaffinity[g] == 0 for g in drawn)
    urdf = ET.parse(robots_dir() / "panda_description" / "urdf" / "panda.urdf").getroot()
    masses = {
        link.get("name"): float(link.find("inertial/mass").get("value"))
        for link in urdf.iter("link")
        if link.find("inertial/mass") is not None
    }
    assert len(masses) >= 10
    for link, mass in masses.items():
        assert model.body_mass[model.body(f"left/{link}").id] == pytest.approx(mass), link


def test_the_spawn_marker_lies_as_the_spawned_brick_does():
    loop = _loop()
    site = loop.model.site("spawn_marker")
    marker_yaw = yaw_of(loop.data.site_xmat[site.id].reshape(3, 3))
    assert marker_yaw == pytest.approx(loop.config.layout.spawn_yaw, abs=1e-9)
    length, width = site.size[:2]
    brick = loop.config.brick
    assert length > width and length == pytest.approx(brick.length / 2, abs=0.01)
    slot = loop.custody.feed_spot()
    body = loop.handles.brick_body[slot]
    mujoco.mj_forward(loop.model, loop.data)
    brick_yaw = yaw_of(loop.data.xmat[body].reshape(3, 3))  # its long side along its own x
    assert abs(np.cos(brick_yaw - marker_yaw)) == pytest.approx(1.0, abs=1e-9)


def _frames(loop: BuildLoop, hide_bricks: bool = False) -> dict[str, np.ndarray]:
    model, rgba = loop.model, loop.model.geom_rgba.copy()
    if hide_bricks:
        for b in loop.handles.brick_body:
            adr = model.body_geomadr[b]
            model.geom_rgba[adr : adr + model.body_geomnum[b], 3] = 0.0
    with HeadlessRenderer(model, 320, 240, "egl") as renderer:
        frames = {}
        for camera in CAMERAS:
            renderer.update_scene(loop.data, camera)
            frames[camera] = renderer.render()
    model.geom_rgba[:] = rgba
    return frames


@pytest.mark.parametrize("robot", ["panda", "baxter"])
def test_every_camera_films_a_lit_lab_without_black_and_without_the_magazine(robot):
    loop = _loop(robot)
    frames, without = _frames(loop), _frames(loop, hide_bricks=True)
    for camera, frame in frames.items():
        top = frame[:8].astype(float).mean()
        assert top > 60, f"{camera}: the top rows are dark ({top:.0f})"
        black_rows = ((frame.max(axis=2) < 20).mean(axis=1) > 0.9).sum()
        assert black_rows == 0, f"{camera}: {black_rows} rows of the frame are black"
        # Every brick is still parked: hiding them changes no pixel of any camera.
        assert np.array_equal(frame, without[camera]), f"{camera} films the magazine"


def test_the_magazine_stays_at_rest_until_a_brick_is_spawned():
    loop = _loop()
    h, d = loop.handles, loop.data
    parked = {s: d.qpos[h.brick_qpos[s] : h.brick_qpos[s] + 3].copy() for s in range(h.n_bricks)}
    stop = {"at": None}

    def watch(data):
        if data.time > 1.0 and stop["at"] is None:
            stop["at"] = data.time
            for slot in range(loop.spawner.next_slot, h.n_bricks):  # never spawned yet
                q = h.brick_qpos[slot]
                assert np.allclose(data.qpos[q : q + 3], parked[slot], atol=1e-4), slot
                assert data.body_awake[h.brick_body[slot]] == 0, f"slot {slot} is awake"

    loop.run(BuildHooks(on_step=watch))
    assert stop["at"] is not None and loop.spawner.next_slot < h.n_bricks


@pytest.mark.parametrize(
    "robot",
    ["panda", pytest.param("baxter", marks=pytest.mark.slow)],  # Baxter's at half speed
)
def test_each_wrist_camera_has_its_brick_in_view_from_approach_to_release(robot):
    """The brick an arm carries (or is about to grip) projects inside its wrist camera's
    image at every control step from the pick's servo to the release."""
    loop = _loop(robot)
    model, data, h = loop.model, loop.data, loop.handles
    arms = loop.config.robot_description.arms
    cams = {a: model.camera(arms[a].wrist_camera).id for a in arms}
    seen: dict[str, int] = {a: 0 for a in arms}

    def in_view(arm: str, slot: int) -> bool:
        cam = cams[arm]
        p = data.xpos[h.brick_body[slot]] - data.cam_xpos[cam]
        x, y, z = data.cam_xmat[cam].reshape(3, 3).T @ p
        half = np.tan(np.radians(model.cam_fovy[cam]) / 2)
        return z < 0 and abs(x / -z) < half and abs(y / -z) < half

    def watch(d):
        for arm in arms:
            step = loop.step_of(arm)
            carry = loop.custody.carry[arm]
            if carry is not None:
                assert in_view(arm, carry.slot), (arm, step.name if step else None, d.time)
                seen[arm] += 1
            elif step is not None and step.name == "servo" and loop.spawner.current is not None:
                assert in_view(arm, loop.spawner.current), (arm, "servo", d.time)

    loop.run(BuildHooks(on_step=watch))
    assert all(n > 100 for n in seen.values()), seen


def _sky_coloured(model: mujoco.MjModel) -> None:
    """The skybox painted magenta, a colour nothing else in the scene has."""
    for t in range(model.ntex):
        if model.tex_type[t] == mujoco.mjtTexture.mjTEXTURE_SKYBOX:
            n = model.tex_width[t] * model.tex_height[t] * model.tex_nchannel[t]
            pixels = model.tex_data[model.tex_adr[t] : model.tex_adr[t] + n]
            pixels.reshape(-1, model.tex_nchannel[t])[:, :3] = [255, 0, 255]


@pytest.mark.parametrize("robot", ["panda", "baxter"])
def test_the_room_fills_every_scene_cameras_frame_however_the_camera_is_moved(robot):
    """No sky behind the scene from the overview, front and top cameras, where they stand and
    moved as far as the randomization moves them (3 cm and 3 degrees about each axis)."""
    loop = _loop(robot)
    model, data = loop.model, loop.data
    _sky_coloured(model)
    moves = [np.zeros(6)] + [np.array(s) for s in itertools.product((-1.0, 1.0), repeat=6)][::7]
    with HeadlessRenderer(model, 96, 72, "egl") as renderer:
        for camera in CAMERAS:
            cam = model.camera(camera).id
            pos, quat = model.cam_pos[cam].copy(), model.cam_quat[cam].copy()
            for move in moves:
                turn, moved = np.zeros(4), np.zeros(4)
                mujoco.mju_euler2Quat(turn, np.radians(3.0 * move[3:]), "xyz")
                mujoco.mju_mulQuat(moved, quat, turn)
                data.cam_xpos[cam] = pos + 0.03 * move[:3]
                mujoco.mju_quat2Mat(data.cam_xmat[cam], moved)
                renderer.update_scene(data, camera)
                frame = renderer.render().astype(int)
                sky = (frame[..., 0] > 150) & (frame[..., 1] < 90) & (frame[..., 2] > 150)
                assert not sky.any(), (camera, move, int(sky.sum()))


def test_a_bricks_faces_are_framed_by_a_darker_border():
    """Every face of a brick is drawn with its texture: white inside, a darker strip at its
    edges, so bricks of one colour side by side or stacked are told apart."""
    model = build_scene(SimConfig(), 2).model
    for slot in range(2):
        t = model.tex(f"brick0{slot}/surface").id
        h, w, c = model.tex_height[t], model.tex_width[t], model.tex_nchannel[t]
        pixels = model.tex_data[model.tex_adr[t] : model.tex_adr[t] + h * w * c]
        pixels = pixels.reshape(h, w, c).astype(int)
        assert (pixels[h // 4 : -h // 4, w // 4 : -w // 4] == 255).all()
        for edge in (pixels[0], pixels[-1], pixels[:, 0], pixels[:, -1]):
            assert (edge < 160).all()
        geom = model.geom(f"brick0{slot}/geom").id
        assert model.mat_texid[model.geom_matid[geom]].max() == t


@pytest.mark.parametrize(
    "robot",
    ["panda", pytest.param("baxter", marks=pytest.mark.slow)],  # Baxter's at half speed
)
def test_each_wrist_camera_sees_both_fingers_and_the_brick_between_them_at_the_grip(robot):
    """As each hand has closed on its first brick, its wrist camera's image holds both fingers
    and the brick (counted in a segmentation render: which geom drew each pixel)."""
    loop = _loop(robot)
    model = loop.model
    arms = loop.config.robot_description.arms
    # a finger: the body its joint moves and what hangs below it (Baxter's paddle tip)
    fingers = {
        a: [
            subtree(model, model.body(int(model.joint(j).bodyid[0])).name)
            for j in arms[a].finger_joints
        ]
        for a in arms
    }
    bricks = set(loop.handles.brick_body)
    last: dict[str, str | None] = {a: None for a in arms}
    counted: dict[str, list[int]] = {}
    renderer = HeadlessRenderer(model, 160, 120, "egl")
    renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = True
    renderer.scene.flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = True

    def watch(d):
        for arm in arms:
            step = loop.step_of(arm)
            name = step.name if step is not None else None
            if last[arm] == "grip" and name != "grip" and arm not in counted:
                renderer.update_scene(d, arms[arm].wrist_camera)
                frame = renderer.render().astype(np.int64)
                ids = frame[..., 0] + (frame[..., 1] << 8) + (frame[..., 2] << 16) - 1
                counts = [0, 0, 0]  # pixels of the one finger, the other, a brick
                for seg, n in zip(*np.unique(ids[ids >= 0], return_counts=True)):
                    geom = renderer.scene.geoms[seg]
                    if geom.objtype != mujoco.mjtObj.mjOBJ_GEOM:
                        continue
                    body = int(model.geom_bodyid[geom.objid])
                    for i, finger in enumerate(fingers[arm]):
                        counts[i] += int(n) if body in finger else 0
                    if body in bricks:
                        counts[2] += int(n)
                counted[arm] = counts
            last[arm] = name

    try:
        loop.run(BuildHooks(on_step=watch))
    finally:
        renderer.close()
    assert set(counted) == set(arms), counted
    for arm, (one, other, brick) in counted.items():
        # of 19200 pixels: each finger at least 0.5 %, the brick at least a tenth
        assert one > 100 and other > 100 and brick > 1920, (arm, counted[arm])
