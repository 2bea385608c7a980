"""Per-episode domain randomization, drawn from the episode's seed, each part switched on by
name: physical parts change the settings the build is made from (and so the compiled model),
visual parts change only what the cameras see, in the compiled model after it is made.

The ranges sit around the defaults, wide enough to vary a policy's inputs and narrow enough
that the scripted expert still builds (its grasp and its reach are those of the defaults).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ...config import SimConfig
from ...errors import ConfigError
from .textures import PATTERNS, texture_pixels

PHYSICAL = ("friction", "brick_mass", "grip_force", "pad_friction", "spawn_jitter", "brick_size")
VISUAL = ("light", "colours", "textures", "camera")
PARTS = PHYSICAL + VISUAL
STREAM = 0x5EED  # the draw's own random stream beside the seed's spawn jitter
SCENE_CAMERAS = ("overview", "front", "top")
COLOURED = ("floor", "wall", "table", "cabinet")  # materials whose colour is drawn, with bricks
TEXTURED = ("floor", "wall", "table", "brick")  # textures drawn (every brick's its own speckle)


ACCEPTED = f"all, none, or some of {', '.join(PARTS)}"


def check_parts(parts: tuple[str, ...]) -> tuple[str, ...]:
    """The parts asked for: "all" alone for every one, "none" alone (or nothing) for none, or
    some of PARTS, each once; ConfigError naming the first that is not so."""
    if isinstance(parts, str):
        raise ConfigError(
            f"randomize: {parts!r} is one name, not a sequence of them; accepted {ACCEPTED}"
        )
    parts = tuple(parts)
    for word in ("all", "none"):
        if word in parts and len(parts) > 1:
            raise ConfigError(
                f"randomize: {word!r} stands alone, not beside {_others(parts, word)}; "
                f"accepted {ACCEPTED}"
            )
    if parts == ("all",):
        return PARTS
    if parts == ("none",):
        return ()
    for part in parts:
        if part not in PARTS:
            raise ConfigError(f"randomize: unknown {part!r}; accepted {ACCEPTED}")
    if len(set(parts)) != len(parts):
        raise ConfigError(f"randomize: {', '.join(parts)} names one twice; accepted each once")
    return parts


def _others(parts: tuple[str, ...], word: str) -> str:
    return ", ".join(repr(p) for p in parts if p != word) or repr(word)


def draw(seed: int, parts: tuple[str, ...]) -> dict[str, Any]:
    """The values of the named parts for the episode of `seed` (plain numbers and lists, as
    the episode's record keeps them)."""
    rng = np.random.default_rng([seed, STREAM])
    drawn: dict[str, Any] = {}
    # Every part draws its numbers whether it is on or not, so one part's values do not depend
    # on which others are switched on.
    values = {
        "friction": float(rng.uniform(0.6, 1.2)),
        "brick_mass": float(rng.uniform(0.3, 0.7)),
        "grip_force": float(rng.uniform(15.0, 25.0)),
        "pad_friction": float(rng.uniform(0.8, 1.2)),
        "spawn_jitter": float(rng.uniform(0.0, 2.0)),
        "brick_size": [float(v) for v in rng.uniform(-0.002, 0.002, 3)],  # m on each side
        "light": {
            "shift": [float(v) for v in rng.uniform(-0.3, 0.3, 3)],
            "intensity": float(rng.uniform(0.7, 1.2)),
        },
        "colours": {
            name: [float(v) for v in rng.uniform(0.8, 1.2, 3)] for name in (*COLOURED, "brick")
        },
        "camera": {
            name: {
                "shift": [float(v) for v in rng.uniform(-0.03, 0.03, 3)],
                "turn": [float(v) for v in rng.uniform(-3.0, 3.0, 3)],
            }
            for name in SCENE_CAMERAS
        },
        # drawn last: the parts above draw what they drew before textures existed
        "textures": {
            name: {
                "pattern": PATTERNS[int(rng.integers(len(PATTERNS)))],
                "cells": int(rng.integers(2, 13)),
                "contrast": float(rng.uniform(0.05, 0.3)),
                "seed": int(rng.integers(2**31)),
            }
            for name in TEXTURED
        },
    }
    for part in parts:
        drawn[part] = values[part]
    return drawn


def physical(config: SimConfig, drawn: dict[str, Any]) -> SimConfig:
    """The settings with the drawn physical parts applied."""
    brick, gripper, layout = config.brick, config.gripper, config.layout
    if "friction" in drawn:
        brick = replace(brick, friction=drawn["friction"])
    if "brick_mass" in drawn:
        brick = replace(brick, mass=drawn["brick_mass"])
    if "brick_size" in drawn:
        dl, dw, dh = drawn["brick_size"]
        brick = replace(
            brick, length=brick.length + dl, width=brick.width + dw, height=brick.height + dh
        )
    if "grip_force" in drawn:
        gripper = replace(gripper, force=drawn["grip_force"])
    if "pad_friction" in drawn:
        gripper = replace(gripper, pad_friction=drawn["pad_friction"])
    if "spawn_jitter" in drawn:
        layout = replace(layout, spawn_jitter_mm=drawn["spawn_jitter"])
    return replace(config, brick=brick, gripper=gripper, layout=layout)


def visual(model: Any, data: Any, drawn: dict[str, Any]) -> None:
    """The drawn visual parts into a compiled model: lights, colours and the scene's cameras,
    and the lights' and cameras' placements in `data` recomputed. Nothing the physics reads
    changes."""
    import mujoco

    if "light" in drawn:
        model.light_pos[:] += np.array(drawn["light"]["shift"])
        model.light_diffuse[:] *= drawn["light"]["intensity"]
    if "colours" in drawn:
        for m in range(model.nmat):
            name = model.material(m).name
            key = "brick" if name.endswith("/brick") else name
            if key in drawn["colours"]:
                model.mat_rgba[m, :3] = np.clip(model.mat_rgba[m, :3] * drawn["colours"][key], 0, 1)
    if "textures" in drawn:
        _draw_textures(model, drawn["textures"])
    if "camera" in drawn:
        for name, move in drawn["camera"].items():
            cam = model.camera(name).id
            model.cam_pos[cam] += np.array(move["shift"])
            turn = np.zeros(4)
            mujoco.mju_euler2Quat(turn, np.radians(move["turn"]), "xyz")
            quat = np.zeros(4)
            mujoco.mju_mulQuat(quat, model.cam_quat[cam], turn)
            model.cam_quat[cam] = quat
    _place_world_frames(model, data)


def _draw_textures(model: Any, textures: dict[str, dict[str, Any]]) -> None:
    """Each drawn surface's texture pixels, around the texture's own mean tone, into the
    model (a renderer made after this uploads them). A brick's pattern is drawn around its
    face's tone and shaded as its own texture is, so the darker border that frames each face
    stays."""
    for t in range(model.ntex):
        name = model.tex(t).name
        key = "brick" if name.endswith("/surface") else name
        if key not in textures:
            continue
        h, w, c = model.tex_height[t], model.tex_width[t], model.tex_nchannel[t]
        adr = model.tex_adr[t]
        pixels = model.tex_data[adr : adr + h * w * c].reshape(h, w, c)
        look = textures[key]
        seed = look["seed"] + t  # every brick its own speckle of the one look
        if key == "brick":
            face = pixels.reshape(-1, c).max(axis=0).astype(float)
            shade = pixels / np.maximum(face, 1.0)
            drawn = texture_pixels(
                look["pattern"], look["cells"], look["contrast"], seed, face / 255.0, h, w
            )
            pixels[:] = np.clip(drawn * shade, 0, 255).round().astype(np.uint8)
            continue
        base = pixels.reshape(-1, c).mean(axis=0) / 255.0
        pixels[:] = texture_pixels(
            look["pattern"], look["cells"], look["contrast"], seed, base, h, w
        )


def _place_world_frames(model: Any, data: Any) -> None:
    """Lights and cameras fixed to the world where the model now puts them: MuJoCo places
    the world's frames once (they never move), so a later forward leaves them as they were."""
    import mujoco

    for cam in range(model.ncam):
        if model.cam_bodyid[cam] == 0:
            data.cam_xpos[cam] = model.cam_pos[cam]
            mujoco.mju_quat2Mat(data.cam_xmat[cam], model.cam_quat[cam])
    for light in range(model.nlight):
        if model.light_bodyid[light] == 0:
            data.light_xpos[light] = model.light_pos[light]
            data.light_xdir[light] = model.light_dir[light]
