"""What a 3D replay needs of a run, kept beside its result: the scene's visible geometry once
(each robot mesh stored once however many geoms share it) and every moving body's pose at
the film's rate, quantized to 0.1 mm and 1/32767 of a unit quaternion. `pyramid-sim replay`
turns the file into a page (replay_page.py); nothing here needs a renderer.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .files import atomic_path

if TYPE_CHECKING:
    import mujoco

    from ..config import VideoConfig
    from ..physics.hooks import BuildHooks
    from ..physics.loop import BuildLoop

FORMAT = 1  # the file's layout; a reader refuses another
POS_UNIT = 1e-4  # m a stored position step is: +-3.2 m in an int16
QUAT_UNIT = 1.0 / 32767.0
VISIBLE_GROUPS = 3  # MuJoCo's viewer shows geom groups 0, 1 and 2 by default
MESH = 7  # mjtGeom's mesh: drawn from its vertices, not its size
REPLAY_FILE = "replay.npz"  # a build's, in its run folder
EPISODES_FOLDER = "replay"  # an evaluation's or a recording's: replay/episode_<index>.npz
SCENE_CAMERA = "overview"
MESH_ARRAYS = ("mesh_vert", "mesh_face", "mesh_vertnum", "mesh_facenum")


def episode_name(index: int) -> str:
    """The file of episode `index` (from 0) in an evaluation's or a recording's replay/."""
    return f"episode_{index:06d}.npz"


def episode_file(folder: Path, index: int) -> Path:
    """Where an evaluation's or a recording's episode `index` keeps its poses."""
    return folder / EPISODES_FOLDER / episode_name(index)


class PoseTape:
    """Call it with (model, data) at each frame; `save` writes the geometry and the poses."""

    def __init__(self, loop: BuildLoop, frame_dt: float, title: str = "") -> None:
        self.frame_dt = float(frame_dt)
        self.title = title
        self.scene = {**scene_of(loop.model), "goal": goals_of(loop)}
        self.bodies = self.scene.pop("bodies")
        self.times: list[float] = []
        self.positions: list[np.ndarray] = []
        self.rotations: list[np.ndarray] = []

    def __call__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.times.append(float(data.time))
        self.positions.append(_quantized(data.xpos[self.bodies], POS_UNIT))
        self.rotations.append(_quantized(data.xquat[self.bodies], QUAT_UNIT))

    @property
    def frames(self) -> int:
        return len(self.times)

    def save(self, path: Path, shared: bool = False, **extra: Any) -> None:
        """The tape as a compressed .npz, written whole or not at all; `extra` arrays beside
        (an episode's seed). `shared`: the meshes go in a file of their own beside it, named
        by their content, that every episode of a folder shares (written once)."""
        scene = dict(self.scene)
        if shared:
            meshes = {k: scene.pop(k) for k in MESH_ARRAYS}
            digest = hashlib.sha1(b"".join(a.tobytes() for a in meshes.values()))
            scene["mesh_file"] = np.str_(f"meshes_{digest.hexdigest()[:16]}.npz")
            if not (path.parent / str(scene["mesh_file"])).exists():
                _write_npz(path.parent / str(scene["mesh_file"]), meshes)
        _write_npz(
            path,
            {
                "format": np.int16(FORMAT),
                "frame_dt": np.float64(self.frame_dt),
                "title": np.str_(self.title),
                "time": np.asarray(self.times, np.float32),
                "pos": np.stack(self.positions).astype(np.int16),
                "quat": np.stack(self.rotations).astype(np.int16),
                **scene,
                **{k: np.asarray(v) for k, v in extra.items()},
            },
        )


def _write_npz(path: Path, arrays: dict[str, Any]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp, tmp.open("wb") as f:
        np.savez_compressed(f, **arrays)


class EpisodeTape:
    """An environment's episode taped into `path`: a frame at its reset and one each step (an
    evaluation's film's rate), its seed kept with it so a reader can tell whose it is, its
    meshes in a file that the folder's episodes share."""

    def __init__(self, path: Path, seed: int) -> None:
        self.path, self.seed = path, seed
        self.tape: PoseTape | None = None

    def start(self, env: Any) -> None:
        """The episode has been reset: its (maybe new) model, and its first frame."""
        loop = env.unwrapped.loop
        self.tape = PoseTape(loop, 1.0 / env.unwrapped.metadata["render_fps"])
        self.step(env)

    def step(self, env: Any) -> None:
        assert self.tape is not None, "step() before start()"
        loop = env.unwrapped.loop
        self.tape(loop.model, loop.data)

    def save(self, title: str) -> None:
        assert self.tape is not None, "save() before start()"
        self.tape.title = title
        self.tape.save(self.path, shared=True, seed=np.int64(self.seed))


class Taping:
    """An environment that tapes its episodes into `tape` (its reset's frame and each step's),
    standing for it everywhere else, so a rollout needs no hook of its own."""

    def __init__(self, env: Any, tape: EpisodeTape) -> None:
        self._env, self._tape = env, tape

    def __getattr__(self, name: str) -> Any:
        return getattr(self._env, name)

    def reset(self, **kwargs: Any) -> Any:
        reset = self._env.reset(**kwargs)
        self._tape.start(self._env)
        return reset

    def step(self, action: Any) -> Any:
        stepped = self._env.step(action)
        self._tape.step(self._env)
        return stepped


def taped(loop: BuildLoop, hooks: BuildHooks, film: VideoConfig) -> tuple[PoseTape, BuildHooks]:
    """A tape of `loop` at the film's rate, and `hooks` that feed it (beside the film's
    recorder, if one is filming: both at the film's frames)."""
    from dataclasses import replace

    tape = PoseTape(loop, film.frame_dt)
    filming = hooks.on_frame
    if filming is None:
        return tape, replace(hooks, on_frame=tape, frame_dt=film.frame_dt)

    def both(model: mujoco.MjModel, data: mujoco.MjData) -> None:
        tape(model, data)
        filming(model, data)

    return tape, replace(hooks, on_frame=both)


def _quantized(values: np.ndarray, unit: float) -> np.ndarray:
    return np.clip(np.round(values / unit), -32767, 32767).astype(np.int16)


def scene_of(model: mujoco.MjModel) -> dict[str, Any]:
    """The visible geoms (their body among the taped ones, shape, size, local pose, colour,
    mesh) and the meshes they use, each distinct one once; `bodies` holds the model's ids."""
    visible = [
        g
        for g in range(model.ngeom)
        if model.geom_group[g] < VISIBLE_GROUPS and _rgba(model, g)[3] > 0
    ]
    bodies = sorted({int(model.geom_bodyid[g]) for g in visible})
    meshes: dict[str, int] = {}
    verts: list[np.ndarray] = []
    faces: list[np.ndarray] = []
    geom_mesh = []
    for g in visible:
        m = int(model.geom_dataid[g]) if model.geom_type[g] == MESH else -1
        if m >= 0:
            v, f = _mesh(model, m)
            key = hashlib.sha1(v.tobytes() + f.tobytes()).hexdigest()
            if key not in meshes:
                meshes[key] = len(verts)
                verts.append(v)
                faces.append(f)
            m = meshes[key]
        geom_mesh.append(m)
    return {
        "bodies": np.asarray(bodies, np.int32),
        "body_names": np.asarray([_name(model, "body", b) for b in bodies], np.str_),
        "geom_body": np.asarray([bodies.index(int(model.geom_bodyid[g])) for g in visible]),
        "geom_type": model.geom_type[visible].astype(np.int8),
        "geom_size": model.geom_size[visible].astype(np.float32),
        "geom_pos": model.geom_pos[visible].astype(np.float32),
        "geom_quat": model.geom_quat[visible].astype(np.float32),
        "geom_rgba": np.asarray([_rgba(model, g) for g in visible], np.float32),
        "geom_mesh": np.asarray(geom_mesh, np.int16),
        "mesh_vert": np.concatenate(verts or [np.zeros((0, 3), np.float32)]),
        "mesh_face": np.concatenate(faces or [np.zeros((0, 3), np.uint16)]),
        "mesh_vertnum": np.asarray([len(v) for v in verts], np.int32),
        "mesh_facenum": np.asarray([len(f) for f in faces], np.int32),
        "camera": _camera(model),
    }


def goals_of(loop: BuildLoop) -> np.ndarray:
    """Where each brick of the plan is to rest: a row a brick, its centre (x, y, z), yaw and
    half sizes (length, width, height), drawn on the page as outlines."""
    brick = loop.config.brick
    half = (brick.length / 2, brick.width / 2, brick.height / 2)
    rows = [
        (b.target.pose.x, b.target.pose.y, b.target.pose.z, b.target.pose.yaw, *half)
        for b in loop.plan.bricks
    ]
    return np.asarray(rows, np.float32).reshape(-1, 7)


def _rgba(model: mujoco.MjModel, g: int) -> np.ndarray:
    """The colour MuJoCo draws a geom in: its material's, if it has one."""
    mat = int(model.geom_matid[g])
    return np.asarray(model.mat_rgba[mat] if mat >= 0 else model.geom_rgba[g], np.float32)


def _mesh(model: mujoco.MjModel, m: int) -> tuple[np.ndarray, np.ndarray]:
    """Mesh `m`'s vertices (in its geom's frame, as compiled) and faces (uint16 per mesh)."""
    v0, nv = int(model.mesh_vertadr[m]), int(model.mesh_vertnum[m])
    f0, nf = int(model.mesh_faceadr[m]), int(model.mesh_facenum[m])
    faces = model.mesh_face[f0 : f0 + nf]
    assert nv < 65536, "a mesh of more vertices than a uint16 indexes"
    return model.mesh_vert[v0 : v0 + nv].astype(np.float32), faces.astype(np.uint16)


def _name(model: mujoco.MjModel, kind: str, i: int) -> str:
    import mujoco

    obj = {"body": mujoco.mjtObj.mjOBJ_BODY, "camera": mujoco.mjtObj.mjOBJ_CAMERA}[kind]
    return mujoco.mj_id2name(model, obj, i) or f"{kind}{i}"


def _camera(model: mujoco.MjModel) -> np.ndarray:
    """Where the page's camera starts: the scene camera's position and a point 1.5 m ahead of
    it (the table, from the overview camera); a default view where the model has none."""
    names = [_name(model, "camera", c) for c in range(model.ncam)]
    if SCENE_CAMERA not in names:
        return np.asarray([2.0, -0.6, 1.0, 0.5, 0.0, 0.75], np.float32)
    import mujoco

    c = names.index(SCENE_CAMERA)
    pos = model.cam_pos[c]  # the scene cameras sit on the world body: these are world poses
    mat = np.zeros(9)
    mujoco.mju_quat2Mat(mat, model.cam_quat[c])
    forward = -mat.reshape(3, 3)[:, 2]  # a camera looks down its -z
    return np.concatenate([pos, pos + 1.5 * forward]).astype(np.float32)
