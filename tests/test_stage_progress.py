"""benchmarks/baseline.py's stages show their progress on a terminal (the recording's
episodes, the training's steps read off lerobot-train's log while it runs, the scoring's
episodes) and nothing in a log; Ctrl-C in a training ends it in one line, exit 130."""

import io
import json
import re
import sys
import threading
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import baseline  # noqa: E402
import row_recording  # noqa: E402
import row_scoring  # noqa: E402
import row_training  # noqa: E402
import stage_progress  # noqa: E402
from rows import Recipe  # noqa: E402

# lerobot-train's log as it writes it (runs/panda-2/train.log): its bar redrawn after a
# carriage return, its INFO lines between
LOG = (
    "INFO 2026-12-04 19:50:26 ot_train.py:448 num_total_params=2672652 (3M)\n"
    "\rTraining:   0%|          | 0/4000 [00:00<?, ?step/s]INFO 2026-12-04 19:50:26 "
    "ot_train.py:597 Start offline training on a fixed dataset, with effective batch size: 32\n"
    "\rTraining:   0%|          | 1/4000 [00:01<1:11:00,  1.07s/step]"
    "\rTraining:   0%|          | 2/4000 [00:01<51:56,  1.28step/s]  "
)
LATE = (
    "\rTraining:  95%|█████████▍| 3799/4000 [38:43<01:31,  2.20step/s]"
    "\rTraining:  95%|█████████▌| 3800/4000 [38:43<01:32,  2.15step/s]INFO 2026-12-04 20:29:10 "
    "ot_train.py:641 step:4K smpl:122K ep:431 epch:2.60 loss:0.314 grdn:0.798 lr:3.0e-04 "
    "updt_s:0.222 data_s:0.234 smp/s:70 l1_loss:0.314\n"
)
CHECKPOINT = (
    "INFO 2026-12-04 20:12:01 ot_train.py:641 step:2K smpl:64K ep:227 epch:1.37 loss:0.329 "
    "grdn:0.772 lr:3.0e-04 updt_s:0.312 data_s:0.346 smp/s:49 l1_loss:0.329\n"
    "INFO 2026-12-04 20:12:01 ot_train.py:687 Checkpoint policy after step 2000\n"
)


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_the_step_is_read_off_a_real_lerobot_train_log():
    assert stage_progress.last_step("INFO 2026-12-04 19:50:23 ot_train.py:280 Logs") is None
    assert stage_progress.last_step(LOG) == 2
    assert stage_progress.last_step(LOG + LATE) == 3800  # not 4000, the rounded "step:4K"
    assert stage_progress.last_step(CHECKPOINT) == 2000
    # a tail cut inside a bar: the cut bar is not read
    assert stage_progress.last_step(LATE[30:]) == 3800
    assert stage_progress.last_step(LATE[5:60]) is None


def _records(root: Path) -> None:
    folder = root / "demos" / "meta" / "pyramid_sim"
    folder.mkdir(parents=True)
    (folder / "episode_000000.json").write_text(json.dumps({"episode_index": 0, "success": 1}))


def _training_writes(monkeypatch, parts: list[str], pause: float = 0.0) -> None:
    """lerobot-train, faked: it writes `parts` to its log, each after `pause` s, and ends
    well."""

    def fake_run(command, stdout, **_):
        for part in parts:
            time.sleep(pause)
            stdout.write(part)
            stdout.flush()
        return type("Done", (), {"returncode": 0})()

    monkeypatch.setattr(row_training.subprocess, "run", fake_run)


def _fake_library(monkeypatch) -> None:
    """pyramid_sim's record and evaluate, faked: two episodes each, heard as the real ones
    tell them."""
    import pyramid_sim

    def record(name, on_frame, on_episode, episodes, **_):
        on_episode(0)
        for episode in range(episodes):
            on_frame(episode, 40)
            on_episode(episode + 1)

    def evaluate(policy, name, on_episode, episodes, **_):
        for _ in range(episodes):
            on_episode({"success": True})
        return type("Evaluation", (), {"scores": {"success_rate": 1.0}})()

    monkeypatch.setattr(pyramid_sim, "record", record)
    monkeypatch.setattr(pyramid_sim, "evaluate", evaluate)


def test_in_a_log_every_stage_is_quiet(tmp_path, monkeypatch, capsys):
    _records(tmp_path)
    _training_writes(monkeypatch, [LOG, LATE])
    _fake_library(monkeypatch)
    recipe = Recipe(demos=2, steps=4000)
    row_recording.record(tmp_path, recipe)
    row_training.train(tmp_path, recipe)
    row_scoring.score(tmp_path / "checkpoint", recipe, 3, None)
    assert capsys.readouterr().err == ""
    assert (tmp_path / "train.log").read_bytes().decode() == LOG + LATE  # lerobot's own


def test_on_a_terminal_each_stage_shows_a_bar_and_the_training_its_steps_while_it_runs(
    tmp_path, monkeypatch
):
    _records(tmp_path)
    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    monkeypatch.setattr(stage_progress, "POLL_S", 0.02)
    _training_writes(monkeypatch, [LOG, LATE, CHECKPOINT], pause=0.3)
    _fake_library(monkeypatch)
    recipe = Recipe(demos=2, steps=4000)
    row_recording.record(tmp_path, recipe)
    assert "recording: 100%" in screen.getvalue() and "2/2" in screen.getvalue()
    row_training.train(tmp_path, recipe)
    shown = screen.getvalue()
    # read while it ran: the log's steps in turn, the time left with each
    assert shown.index("| 2/4000 [") < shown.index("| 3800/4000 [")
    assert re.search(r"\| 3800/4000 \[\d\d:\d\d<\d\d:\d\d", shown)  # the time left
    assert "training:" in shown and "4000/4000" not in shown  # never more than it showed
    row_scoring.score(tmp_path / "checkpoint", recipe, 3, tmp_path / "scored")
    assert "scoring scored: 100%" in screen.getvalue() and "3/3" in screen.getvalue()
    assert not [t for t in threading.enumerate() if t.name == "training-log"]


def test_ctrl_c_in_the_training_ends_in_one_line_and_130(tmp_path, monkeypatch):
    out = tmp_path / "run"
    _records(out)
    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    monkeypatch.setattr(stage_progress, "POLL_S", 0.02)

    def interrupted(command, stdout, **_):
        stdout.write(LOG)
        stdout.flush()
        time.sleep(0.2)
        raise KeyboardInterrupt

    monkeypatch.setattr(row_training.subprocess, "run", interrupted)
    monkeypatch.setattr(baseline, "lerobot_needed", lambda what: None)
    monkeypatch.setattr(baseline, "check_recipe", lambda recipe: None)
    monkeypatch.setattr(baseline, "record", lambda out, recipe: 0.0)
    assert baseline.main(["--out", str(out)]) == 130
    shown = screen.getvalue()
    assert shown.endswith("\nbenchmarks/baseline.py: interrupted\n") and "Traceback" not in shown
    assert "2/" in shown  # the bar was there, and stopped
    assert not [t for t in threading.enumerate() if t.name == "training-log"]
    assert not (out / "train_cpu_s.txt").exists() and not (out / "failed.txt").exists()


@pytest.mark.parametrize("tty", [False, True])
def test_a_log_not_yet_written_is_waited_for(tmp_path, tty):
    progress = stage_progress.Progress("training", 10, "step", stream=Terminal(), quiet=not tty)
    with progress, stage_progress.following(tmp_path / "none.log", progress, every=0.01):
        progress.start()
        time.sleep(0.05)
    assert progress.n == 0
