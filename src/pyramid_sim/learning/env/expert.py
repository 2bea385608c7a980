"""The scripted builder as a policy, where docs/learning.md's example imports it from: it
lives with its closed loop in learning/expert/policy.py."""

from ..expert.policy import ExpertPolicy

__all__ = ["ExpertPolicy"]
