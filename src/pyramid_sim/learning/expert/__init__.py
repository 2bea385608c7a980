"""The scripted builder as a policy (`policy.ExpertPolicy`) and its closed loop, given to
each episode's build loop when it is made: the measured tool and brick (`tool_feedback`), a
brick let go off its target set right (`re_place`), the arm's twist damped
(`twist_damping`)."""

__all__ = ["closure", "re_place", "tool_feedback", "twist_damping"]
