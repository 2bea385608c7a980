"""For robot learning, grouped by role as lerobot groups its own (envs, datasets, policies,
scripts), each floor importing only those below it (tests/test_layers.py):

- `task`: what an episode is and what a policy sees of it (variation, randomization, the
  observation's layout, spaces and named entries, the footprint, rewards and endings);
- `action_modes`: what an action is and how it moves the arms, one class a mode, found by
  name (`action_modes.registry`);
- `expert`: the scripted builder as a policy (`expert.policy.ExpertPolicy`), and its closed
  loop, given to each episode's build loop when it is made;
- `env`: the build as a Gymnasium environment (`env.env.BuildEnv`, registered as
  `pyramid_sim/Build-v0` when pyramid_sim is imported): an action's way from its mode through
  the control steps to the build loop;
- `dataset`: LeRobot's v3.0 layout and metadata;
- `recording`: the expert's episodes at a dataset's rate, filmed and landed as a dataset
  (`pyramid-sim record`);
- `lerobot_plugin`: what lerobot's own tools load (`lerobot-eval`'s environment, a
  `lerobot-train` checkpoint as a policy);
- `evaluation`: policies scored over held-out seeds (`pyramid-sim evaluate`), a lerobot
  checkpoint among them, and the perturbations their errors are measured with.

Importing the package imports none of its modules (the environment needs MuJoCo); `__all__`
names the rooms.
"""

__all__ = [
    "action_modes",
    "dataset",
    "env",
    "evaluation",
    "expert",
    "lerobot_plugin",
    "recording",
    "task",
]
