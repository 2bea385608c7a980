"""The leaderboard's rows, each a whole recipe by name: the task, the demonstrations, DAgger's
rounds, the policy and its training, and the evaluation. `benchmarks/baseline.py --row NAME`
runs one end to end; its result file lands in benchmarks/results/NAME.json, and
`benchmarks/leaderboard.py` writes docs/benchmark.md's table from those files."""

from __future__ import annotations

from dataclasses import dataclass, replace

from pyramid_sim.choices import ACTION_MODE_TRACKS, RECORD_IMAGE_SIZE
from pyramid_sim.learning.task.spec import TaskSpec
from pyramid_sim.robots import DEFAULT_ROBOT


@dataclass(frozen=True)
class Round:
    """One DAgger round: `episodes` more episodes recorded with the last policy driving the
    spans its expert does not (`beta` the expert's share), then the policy trained on for
    `steps` more on everything kept. With `takeover` (m), HG-DAgger's gate: the learner's
    drift kept within it, the expert taking over past it (`record --takeover`); without,
    the learner pulled back to within 5 mm of the expert's way."""

    episodes: int
    beta: float
    steps: int
    takeover: float | None = None


@dataclass(frozen=True)
class Recipe:
    """Everything that makes the row: the task, the demonstrations, the policy and its
    training, DAgger's rounds and the evaluation."""

    row: str = "panda-2"
    # the policy family lerobot-train trains: act or diffusion (benchmarks/families.py)
    policy: str = "act"
    robot: str = DEFAULT_ROBOT
    structure: str = "pyramid-even"
    layers: int = 1
    variation: str = "layout"
    cameras: tuple[str, ...] = ()
    # record's default: a default recording's checkpoint evaluates as is
    image_size: tuple[int, int] = RECORD_IMAGE_SIZE
    # the bricks' poses observed (False: the policy sees the bricks through its cameras alone)
    brick_poses: bool = True
    # every goal observed (False: each arm's next alone, so a policy meets any size of the task)
    all_goals: bool = True
    demos: int = 200  # DART's noise leaves about 4 in 5 built: about 160 to learn from
    noise: float = 0.005  # m: DART's offsets on each hand's executed x, y and z
    # s filmed after each build's success: ending there, a demonstration held a few frames
    # after the last release and the policy held its last brick over the target to the end
    # (docs/notes/2026-11-28-learning.md, "The last release, filmed")
    linger: float = 2.0
    # where each hand goes, from the pick location, its clear pose or its next target: the
    # place is copied from the observation, not regressed (docs/env.md, "anchored")
    action_mode: str = "anchored"
    # the recording's rate, the policy's and the evaluation's: an episode of about 210 steps,
    # a chunk of 20 covering 2 s
    fps: int = 10
    steps: int = 4000  # about 20 minutes on an idle core at 3.5 steps a second
    learning_rate: float = 3e-4  # ACT's default 1e-5 took 7000 steps to reach 500's loss
    batch_size: int = 32
    save_every: int = 1000
    dim_model: int = 256
    heads: int = 4
    feedforward: int = 1024
    encoder_layers: int = 2
    decoder_layers: int = 1
    vae: bool = False  # its KL term fell to 0 in every run: a deterministic expert
    # Diffusion Policy's (policy="diffusion"): observations it conditions on, its U-Net's
    # widths, DDIM's denoising steps at run time; its horizon is `chunk`
    obs_steps: int = 2
    down_dims: tuple[int, ...] = (64, 128, 256)
    inference_steps: int = 10
    # ACT's default normalizes state, images and actions but not the environment state (the
    # bricks, goals and hands): a policy trained so ignored them
    normalize_environment: bool = True
    # each chunk of 2 s executed whole: replanning every 0.5 s, the policy put the release
    # ahead of itself at every replan and held the brick over its target
    chunk: int = 20
    action_steps: int = 20
    rounds: tuple[Round, ...] = ()  # DAgger's, after the first training
    round_episodes: int = 0  # each round's policy scored on this many seeds: DAgger's gain
    episodes: int = 100
    # the structure's size the last policy is scored at, where not its training's: a policy
    # that saw each arm's next goal alone (all_goals False) meets any size of the task
    eval_layers: int | None = None
    max_steps: int | None = None
    curve_episodes: int = 0
    workers: int = 1  # episodes recorded and evaluated at once (the data and scores the same)

    @property
    def track(self) -> str:
        """keypose or continuous: the track the leaderboard reports the row in (as RLBench
        reports its keyframe methods apart from continuous control)."""
        return ACTION_MODE_TRACKS[self.action_mode]

    @property
    def task(self) -> TaskSpec:
        """The row's task spec, checked as every caller's is: what its demonstrations are
        recorded on and its policy scored on (`pyramid_sim.record(recipe.task, ...)`)."""
        return TaskSpec(
            self.structure,
            layers=self.layers,
            robot=self.robot,
            variation=self.variation,
            fps=self.fps,
            action_mode=self.action_mode,
            cameras=self.cameras,
            image_size=self.image_size,
            brick_poses=self.brick_poses,
            all_goals=self.all_goals,
            linger=self.linger,
        )


# the six-brick pyramid: DART's 5 mm over six bricks left a third of the demos built, 3 mm
# four in five
SIX = Recipe(row="panda-6", layers=2, demos=220, noise=0.003, steps=10000, save_every=2000)
# DE NIRO's own 20-brick pyramid, by a policy trained on it: the task's goals and the
# arms alone (no brick's pose, each arm's next goal but no other); DART's offsets 2 mm
# (3 mm left one of two 20-brick demonstrations built, the other at the step limit);
# 60 demonstrations (56 built, about 2800 frames each, 157k frames). 6000 steps of 32
# (1.2 passes over the frames) placed 4.60 of 20, 15000 (3 passes, 48 min of one
# core) 12.2 and one whole pyramid, 25000 (resumed from 15000) 8.15 and none
# (results/diagnostics/panda-20-25000-steps.json)
ROW_20 = replace(
    SIX,
    row="panda-20",
    layers=4,
    brick_poses=False,
    all_goals=False,
    demos=60,
    noise=0.002,
    steps=15000,
    save_every=5000,
    episodes=20,
)
ROWS: dict[str, Recipe] = {
    r.row: r
    for r in (
        # the two-brick task, the recipe the first learned rows were found with
        Recipe(),
        # ACT trained on them, then a DAgger round (the learner drives half the spans), each
        # round's policy scored on 50 seeds
        replace(SIX, rounds=(Round(100, 0.5, 3000),), round_episodes=50),
        # the two-brick task's policy, then a round of HG-DAgger: the learner drives half the
        # spans, its drift kept within 2 cm of the expert's way, the expert taking over past
        # it; scored on the same 100 seeds as panda-2 (81/100 before the round)
        Recipe(row="panda-2-hg", rounds=(Round(100, 0.5, 3000, takeover=0.02),)),
        # its control: the same policy trained as many steps (4000 + 3000) on the expert's
        # demonstrations alone, so the round's gain is its data's, not its steps'
        Recipe(row="panda-2-long", steps=7000),
        ROW_20,
        # the 20-brick policy and a round of HG-DAgger: 20 episodes, the learner driving half
        # the spans within 2 cm of the expert's way, then 3000 steps on
        replace(ROW_20, row="panda-20-hg", rounds=(Round(20, 0.5, 3000, takeover=0.02),)),
        # the same policy and a round four times the size: 80 episodes of HG-DAgger at the
        # same gate (211k frames, beside the demonstrations' 176k), then 5000 steps on
        replace(ROW_20, row="panda-20-hg2", rounds=(Round(80, 0.5, 5000, takeover=0.02),)),
        # the 20-brick task with more than three times the demonstrations (200, the 2-brick
        # row's count: 56 built of 60 was a third of the 2- and 6-brick rows' per placement),
        # trained from scratch to a length sized to them: 20000 steps of 32 (about 1.2 passes
        # over their frames, 60 min of one core); every policy trained on past 15000 steps of
        # the 60 placed fewer. 13.85 placed, 1/20 whole: 9 episodes end setting a top brick
        # down a layer low, as its labels give the top approaches from the target below
        # (docs/notes/2026-12-05-occupied-targets.md)
        replace(ROW_20, row="panda-20-200", demos=200, steps=20000),
        # every randomization drawn: friction, mass, grip force, brick size, looks
        Recipe(row="panda-2-full", variation="full"),
        # lerobot's own arm at its scale: DART's offsets a quarter of the Panda's
        Recipe(row="so101-2", robot="so101", noise=0.00125),
        # the continuous track: each hand's bounded pose change from where it is measured,
        # nothing copied from the observation into the action
        Recipe(row="panda-2-delta", action_mode="delta"),
        # the continuous track in absolute targets: each hand's pose in the world, bounded as
        # a delta is; a chunk of places does not carry its first error into its last. At 4000
        # steps (1.7 passes over its 77k frames) its places are 1.5 cm off on the expert's own
        # states (docs/notes/2026-12-04-rows.md)
        Recipe(row="panda-2-absolute", action_mode="absolute"),
        # its policy trained three times as long (its 4000-step targets are 1.5 cm off, and
        # with ACT's temporal ensembling it still pressed the first brick at the spot: 0/10),
        # then a round of HG-DAgger in the mode: the learner's own absolute targets kept within
        # 2 cm of the expert's, the expert taking over past them
        Recipe(
            row="panda-2-absolute-hg",
            action_mode="absolute",
            steps=12000,
            save_every=4000,
            rounds=(Round(100, 0.5, 3000, takeover=0.02),),
        ),
        # the bricks seen through the overview camera alone (96 x 96), their poses unobserved:
        # a step costs about five times the state policy's, so half the steps
        Recipe(
            row="panda-2-camera",
            cameras=("overview",),
            image_size=(96, 96),
            brick_poses=False,
            steps=2000,
        ),
        # a second policy family on the 2-brick keypose task: lerobot's Diffusion Policy sized
        # for a CPU (docs/benchmark.md says how), trained on panda-2's demonstrations
        # (a 64-128-256 U-Net, 5 M weights, a horizon of 16 with 8 executed, as its authors'
        # 10 Hz tasks: 0.13 s a step of 32 on one core, where 128-256-512 and a horizon of 32
        # in batches of 64 took 1.0 s, and 4 s with lerobot's loading)
        Recipe(
            row="panda-2-diffusion",
            policy="diffusion",
            chunk=16,
            action_steps=8,
            down_dims=(64, 128, 256),
            learning_rate=1e-4,
            steps=5000,
            # scored on 50 seeds: an episode that runs to the 900-step limit takes 43 s of a
            # core (ACT's built ones take 4), and the session's two cores train two rows beside
            episodes=50,
        ),
    )
}
QUICK = dict(
    demos=2,
    noise=0.0,
    steps=4,
    save_every=2,
    batch_size=4,
    dim_model=64,
    heads=2,
    feedforward=128,
    encoder_layers=1,
    decoder_layers=1,
    chunk=10,
    action_steps=10,
    episodes=2,
    max_steps=100,
    rounds=(),
)


# Diffusion Policy's horizon a multiple of its U-Net's downsampling (2 for two widths), and
# room for the observations and the executed actions in it
QUICK_DIFFUSION = dict(chunk=8, action_steps=4, down_dims=(16, 32), inference_steps=2)


def quick(recipe: Recipe) -> Recipe:
    """A few of each, for CI's round trip: the row's task, a tiny policy."""
    small = {**QUICK, **(QUICK_DIFFUSION if recipe.policy == "diffusion" else {})}
    return replace(recipe, **small)  # type: ignore[arg-type]
