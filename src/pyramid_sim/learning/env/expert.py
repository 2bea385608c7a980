"""The scripted builder as a policy, kept importable where earlier docs imported it from: it
lives with its closed loop in learning/expert/policy.py."""

from ..expert.policy import ExpertPolicy

__all__ = ["ExpertPolicy"]
