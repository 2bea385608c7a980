"""Per-episode randomization: each part, switched on by name, drawn from the episode's seed,
reaches the compiled model (the physical ones) or the picture (the visual ones), and a part
left off changes nothing."""

import os

import gymnasium
import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.learning.task import randomize as rnd

os.environ.setdefault("MUJOCO_GL", "egl")
ENV = pyramid_sim.ENV_ID


def _env(parts, **extra):
    """At the `fixed` level: only the parts asked for are drawn."""
    return gymnasium.make(
        ENV, structure="pyramid", layers=1, randomize=parts, variation="fixed", **extra
    ).unwrapped


def test_the_draw_is_the_seeds_and_each_part_its_own():
    assert rnd.draw(3, rnd.PARTS) == rnd.draw(3, rnd.PARTS)
    assert rnd.draw(3, rnd.PARTS) != rnd.draw(4, rnd.PARTS)
    alone = rnd.draw(3, ("friction",))
    assert alone == {"friction": rnd.draw(3, rnd.PARTS)["friction"]}  # not moved by the others
    with pytest.raises(pyramid_sim.ConfigError, match="randomize: unknown 'gravity'"):
        rnd.check_parts(("gravity",))


@pytest.mark.parametrize(
    "parts, words",
    [
        (("all", "friction"), "randomize: 'all' stands alone, not beside 'friction'; accepted "
         "all, none, or some of friction, brick_mass"),
        (("friction", "none"), "randomize: 'none' stands alone, not beside 'friction'"),
        (("friction", "friction"), "randomize: friction, friction names one twice; accepted "
         "each once"),
        ("friction", "randomize: 'friction' is one name, not a sequence of them"),
    ],
)  # fmt: skip
def test_the_parts_read_as_the_help_says_them(parts, words):
    """`all` and `none` each alone (--help's default is none), a part once, as the cameras;
    `all` beside another part was refused as "unknown 'all'" while the list named it."""
    assert rnd.check_parts(("all",)) == rnd.PARTS and rnd.check_parts(("none",)) == ()
    with pytest.raises(pyramid_sim.ConfigError) as refused:
        rnd.check_parts(parts)
    assert words in str(refused.value)


def test_a_recording_of_no_parts_is_the_same_whether_said_none_or_left_out():
    from pyramid_sim.learning.recording.record_config import RecordConfig

    assert RecordConfig(randomize=("none",)) == RecordConfig()  # one recording, resumable


def test_each_physical_part_reaches_the_compiled_model():
    env = _env(rnd.PHYSICAL)
    _, info = env.reset(seed=5)
    drawn = info["randomization"]
    m, robot = env.loop.model, env.loop.config.robot_description
    brick = m.geom("brick00/geom")
    assert brick.friction[0] == pytest.approx(drawn["friction"])
    assert m.geom("table_top").friction[0] == pytest.approx(drawn["friction"])
    assert m.body("brick00/brick").mass[0] == pytest.approx(drawn["brick_mass"])
    base = np.array([0.192, 0.086, 0.062])
    np.testing.assert_allclose(brick.size * 2, base + np.array(drawn["brick_size"]), atol=1e-12)
    pad = m.geom(robot.arms["left"].pads[0])
    assert pad.friction[0] == pytest.approx(drawn["pad_friction"])
    for arm in ("left", "right"):  # the gripper pulls and pushes with the drawn force
        grip = m.actuator(robot.arms[arm].gripper_actuator)
        force = drawn["grip_force"]
        np.testing.assert_allclose(grip.forcerange, [-force, force], rtol=1e-12, err_msg=arm)
    jitter = m.geom("spawn_volume").size[0] - brick.size[0]
    assert jitter == pytest.approx(drawn["spawn_jitter"] / 1000.0)
    assert env.loop.config.layout.spawn_jitter_mm == pytest.approx(drawn["spawn_jitter"])
    env.close()


def test_each_visual_part_changes_the_picture_and_nothing_the_physics_reads():
    plain = _env((), cameras=("overview",), image_size=(48, 64))
    obs_plain, _ = plain.reset(seed=5)
    for _ in range(3):
        plain.step(plain.expert_action())
    qpos_plain = plain.loop.data.qpos.copy()
    for part in rnd.VISUAL:
        env = _env((part,), cameras=("overview",), image_size=(48, 64))
        obs, info = env.reset(seed=5)
        m, p = env.loop.model, plain.loop.model
        assert not np.array_equal(obs["images"]["overview"], obs_plain["images"]["overview"]), part
        for field in ("geom_friction", "body_mass", "geom_size", "actuator_forcerange"):
            assert np.array_equal(getattr(m, field), getattr(p, field)), (part, field)
        for option in (o for o in dir(p.opt) if not o.startswith("_")):
            assert np.array_equal(getattr(m.opt, option), getattr(p.opt, option)), (part, option)
        changed = {
            "light": ("light_pos", "light_diffuse"),
            "colours": ("mat_rgba",),
            "textures": ("tex_data",),
            "camera": ("cam_pos", "cam_quat"),
        }[part]
        for field in changed:
            assert not np.array_equal(getattr(m, field), getattr(p, field)), (part, field)
        assert set(info["randomization"]) == {part}
        drawn = {field: getattr(m, field).copy() for field in changed}
        for _ in range(3):  # the physics steps on; what was drawn stays drawn
            env.step(env.expert_action())
        if part == "camera":
            cam = m.camera("overview").id
            np.testing.assert_allclose(env.loop.data.cam_xpos[cam], m.cam_pos[cam])
        for field in changed:
            assert np.array_equal(getattr(m, field), drawn[field]), (part, field)
        # and the arms moved as in the plain episode, bit for bit
        assert np.array_equal(env.loop.data.qpos, qpos_plain), part
        env.close()
    plain.close()


def test_the_expert_still_builds_under_every_part():
    env = _env(("all",))
    obs, info = env.reset(seed=2)
    assert set(info["randomization"]) == set(rnd.PARTS)
    while True:
        obs, _, terminated, truncated, info = env.step(env.expert_action())
        if terminated or truncated:
            break
    assert info["is_success"], info["failure"]
    env.close()


def test_drawn_textures_are_the_compiled_models_and_the_films():
    """Each surface's texture in the compiled model is the drawn pattern around its own tone
    (every brick its own speckle of one look), and a renderer made for the episode draws it."""
    from pyramid_sim.learning.task.textures import texture_pixels

    env = _env(("textures",), cameras=("overview",), image_size=(48, 64))
    _, info = env.reset(seed=7)
    looks, m = info["randomization"]["textures"], env.loop.model
    plain = _env(())
    plain.reset(seed=7)
    for name, key in (("floor", "floor"), ("table", "table"), ("brick00/surface", "brick")):
        t = m.tex(name).id
        h, w, c = m.tex_height[t], m.tex_width[t], m.tex_nchannel[t]
        span = slice(m.tex_adr[t], m.tex_adr[t] + h * w * c)
        before = plain.loop.model.tex_data[span].reshape(h, w, c)
        look = looks[key]
        flat = before.reshape(-1, c)
        tone = (flat.max(axis=0) if key == "brick" else flat.mean(axis=0)) / 255.0
        want = texture_pixels(
            look["pattern"], look["cells"], look["contrast"], look["seed"] + t, tone, h, w
        )
        if key == "brick":  # shaded as the brick's own texture: its faces keep their border
            shade = before / flat.max(axis=0)
            want = np.clip(want * shade, 0, 255).round().astype(np.uint8)
            got = m.tex_data[span].reshape(h, w, c).astype(int)
            assert got[0].mean() < 0.8 * got[h // 2].mean()
        np.testing.assert_array_equal(m.tex_data[span].reshape(h, w, c), want)
        assert np.ptp(want.astype(int)) > 0, name  # a pattern, not a flat colour
    bricks = []
    for i in range(2):
        t = m.tex(f"brick0{i}/surface").id
        size = m.tex_height[t] * m.tex_width[t] * m.tex_nchannel[t]
        bricks.append(m.tex_data[m.tex_adr[t] : m.tex_adr[t] + size])
    random = looks["brick"]["pattern"] in ("speckle", "blotches")  # seeded: each brick its own
    assert np.array_equal(bricks[0], bricks[1]) is not random
    env.close()
    plain.close()
