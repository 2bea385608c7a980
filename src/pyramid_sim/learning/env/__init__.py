"""The build as a Gymnasium environment (`env.BuildEnv`): an episode's own count and end
(`episode_state`), and one environment step's control steps (`control_steps`), the action
mode (learning/action_modes/) turning the action into joint commands."""

__all__ = ["control_steps", "env", "episode_state", "expert"]
