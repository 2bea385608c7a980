"""Throughput figures of one machine, measured in one process and one run (benchmarks/run.py).

Every rate is set against physics measured in the same run (the bare step on the same model, and
the build's own physics replayed alone), because these machines are noisy: two runs minutes
apart differ by up to 2x in absolute speed.

    figures.py   what is measured (`BenchConfig`, `run_all`)
    learning_figures.py  the environment's and the recorder's speed against the build's
    targets.py   what each figure is held to, and the printed table
    timers.py    timers wrapped round the calls the IK cannot do without
"""

__all__ = ["figures", "learning_figures", "targets", "timers"]
