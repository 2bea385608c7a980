"""The scripted builder's demonstrations recorded as LeRobot datasets: an episode's frames
(`episode`, led labels in `lead_labels`), filmed (`filming`), staged and landed in order
(`staging`), and `pyramid-sim record` itself (`record`, `record_config`)."""

__all__ = [
    "episode",
    "filming",
    "frame",
    "lead_labels",
    "record",
    "record_config",
    "staging",
]
