"""What lerobot's own tools load: the environment as `lerobot-eval` reads one, and a
`lerobot-train` checkpoint driven as a policy."""

__all__ = [
    "lerobot_env",
    "lerobot_policy",
    "plugin_task",
]
