"""`pyramid-sim sweep --backend ray --ray-address` against a real two-node Ray cluster.

The cluster is started as docs/sweeps.md's recipe says, on a head that has never run Ray: a token
made with `ray get-auth-token --generate`, then `ray start --head` and `ray start --address` for a
second node, both on this machine with one CPU each, every command with RAY_AUTH_MODE=token. A
sweep with it set runs its two builds on the two nodes; a client elsewhere (no token, no
RAY_AUTH_MODE) is told, in one line, what to set.

Every Ray process runs with HOME and RAY_TMPDIR in this module's own temporary folders, so the
token and Ray's session files land there and go with them, whatever the user's own ~/.ray holds.
Each `ray start` runs in a session of its own, so the Ray processes it leaves behind (GCS,
raylet, agents, workers) are exactly the processes of that session: the finalizer stops those
(and any process naming this cluster's temporary folder), never another Ray on the machine.
"""

from __future__ import annotations

import csv
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

# It starts and stops a Ray cluster: one Ray at a time under pytest-xdist (.ci/run).
pytestmark = [pytest.mark.physics, pytest.mark.slow, pytest.mark.xdist_group("ray")]

GRID = ["--structure", "pyramid-even", "--layers", "1", "--friction", "0.6,0.8", "--workers", "2"]
FRICTIONS = ["0.6", "0.8"]
# Environment variables that would change how Ray starts or whom a client talks to.
RAY_SETTINGS = ("RAY_AUTH_MODE", "RAY_ADDRESS", "RAY_AUTH_TOKEN", "RAY_AUTH_TOKEN_PATH")

_NODES_SCRIPT = """
import json, logging, sys
import ray
ray.init(address=sys.argv[1], logging_level=logging.ERROR, log_to_driver=False)
nodes = [{"id": n["NodeID"], "ip": n["NodeManagerAddress"], "cpus": n["Resources"].get("CPU")}
         for n in ray.nodes() if n["Alive"]]
ray.shutdown()
print("NODES " + json.dumps(nodes))
"""


def _ray_cli() -> str:
    try:
        import ray  # noqa: F401
    except ImportError:
        pytest.fail("ray is not importable: the test extra installs it (pip install -e '.[test]')")
    beside = Path(sys.executable).with_name("ray")  # the CLI of this interpreter's Ray
    found = str(beside) if beside.exists() else shutil.which("ray")
    if found is None:
        pytest.fail("the `ray` command line is missing though ray imports: reinstall ray")
    return found


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("", 0))  # the GCS listens on every interface
        return s.getsockname()[1]


def _env(home: Path, temp_dir: str, token: bool) -> dict[str, str]:
    """This process's environment without Ray settings, with `home` as HOME and Ray's
    temporary files in `temp_dir`; RAY_AUTH_MODE=token if `token`. Usage statistics are off:
    nothing here may contact another host."""
    env = {k: v for k, v in os.environ.items() if k not in RAY_SETTINGS}
    env.update(HOME=str(home), RAY_TMPDIR=temp_dir, RAY_USAGE_STATS_ENABLED="0")
    if token:
        env["RAY_AUTH_MODE"] = "token"
    return env


def _session_of(pid: int) -> int | None:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    return int(stat.rsplit(")", 1)[1].split()[3])  # state, ppid, pgrp, session


def _names(pid: int, text: str) -> bool:
    try:
        return text.encode() in Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return False


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _ours(sessions: set[int], temp_dir: str) -> list[int]:
    """The live processes of this cluster: in a session of one of our `ray start`s, or naming
    its temporary folder."""
    me = os.getpid()
    pids = [int(p) for p in os.listdir("/proc") if p.isdigit() and int(p) != me]
    return [p for p in pids if (_session_of(p) in sessions or _names(p, temp_dir)) and _alive(p)]


def _stop(sessions: set[int], temp_dir: str) -> None:
    """SIGTERM every process of this cluster, SIGKILL what is left after 2 s (as `ray stop
    --force` would at once: the GCS server does not end on SIGTERM); raises if any is still
    running after that."""
    for sig, grace in ((signal.SIGTERM, 2.0), (signal.SIGKILL, 10.0)):
        pids = _ours(sessions, temp_dir)
        for pid in pids:
            try:
                os.kill(pid, sig)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + grace
        while pids and time.monotonic() < deadline:
            time.sleep(0.2)
            pids = _ours(sessions, temp_dir)
        if not pids:
            return
    raise RuntimeError(f"Ray processes of the test cluster still running: {pids}")


def _ray(ray: str, args: list[str], env: dict[str, str], sessions: set[int]) -> str:
    """`ray ARGS` in a session of its own; what it printed."""
    proc = subprocess.Popen(
        [ray, *args],
        env=env,
        start_new_session=True,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
    )
    sessions.add(proc.pid)  # its session id: the daemons it leaves keep it
    try:
        out, _ = proc.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, _ = proc.communicate()
    assert proc.returncode == 0, f"ray {' '.join(args)} failed:\n{out}"
    return out


def _alive_nodes(address: str, count: int, env: dict[str, str]) -> list[dict]:
    """The cluster's alive nodes, as a client with RAY_AUTH_MODE=token sees them, once there
    are `count` of them (or after 60 s)."""
    deadline = time.monotonic() + 60
    while True:
        done = subprocess.run(
            [sys.executable, "-c", _NODES_SCRIPT, address],
            check=False,
            env=env,
            capture_output=True,
            text=True,
            timeout=120,
        )
        lines = [ln for ln in done.stdout.splitlines() if ln.startswith("NODES ")]
        nodes = json.loads(lines[-1][6:]) if done.returncode == 0 and lines else []
        if len(nodes) >= count or time.monotonic() > deadline:
            return nodes
        time.sleep(1)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A head and a worker node on this machine, one CPU each, started by docs/sweeps.md's recipe
    on a head that has never run Ray; yields its address (as a user on the head types it), its
    nodes before any sweep, its temporary folder, the head's HOME and what `ray start --head`
    printed."""
    ray = _ray_cli()
    home = tmp_path_factory.mktemp("head-home")  # empty: this head has never run Ray
    temp_dir = tempfile.mkdtemp(prefix="rc", dir="/tmp")  # short: Ray's socket paths live in it
    sessions: set[int] = set()
    port = _free_port()
    address = f"127.0.0.1:{port}"
    env = _env(home, temp_dir, token=True)
    common = [
        "--node-ip-address=127.0.0.1",
        "--num-cpus=1",
        f"--temp-dir={temp_dir}",
        "--object-store-memory=200000000",
        "--disable-usage-stats",
    ]
    try:
        _ray(ray, ["get-auth-token", "--generate"], env, sessions)
        assert (home / ".ray" / "auth_token").read_text().strip(), "no token was made"
        head_out = _ray(
            ray,
            ["start", "--head", f"--port={port}", "--include-dashboard=false", *common],
            env,
            sessions,
        )
        _ray(ray, ["start", f"--address={address}", *common], env, sessions)
        nodes = _alive_nodes(address, 2, env)
        yield {
            "address": address,
            "nodes": nodes,
            "temp_dir": Path(temp_dir),
            "home": home,
            "head_out": head_out,
        }
    finally:
        try:
            _stop(sessions, temp_dir)
        finally:
            shutil.rmtree(temp_dir, ignore_errors=True)


def _sweep(address: str, out: Path, env: dict[str, str]) -> subprocess.CompletedProcess:
    cmd = [
        sys.executable,
        "-m",
        "pyramid_sim.cli",
        "sweep",
        *GRID,
        "--backend",
        "ray",
        "--ray-address",
        address,
        "--out",
        str(out),
        "--quiet",
    ]
    return subprocess.run(cmd, check=False, env=env, capture_output=True, text=True, timeout=300)


def _rows(path: Path) -> list[dict]:
    with open(path) as f:
        return list(csv.DictReader(f))


def _nodes_that_ran(logs: Path, task: str) -> set[str]:
    """The node ids of the Ray workers that ran `task`, from the session's worker logs
    (worker-<id>-<job>-<pid>.out names the tasks; python-core-worker-<id>_<pid>.log the node)."""
    nodes = set()
    for out in logs.glob("worker-*.out"):
        if f":task_name:{task}" not in out.read_text(errors="replace").splitlines():
            continue
        worker_id, pid = out.stem.split("-")[1], out.stem.split("-")[-1]
        core = (logs / f"python-core-worker-{worker_id}_{pid}.log").read_text(errors="replace")
        nodes.update(re.findall(r"node_id=([0-9a-f]+)", core)[:1])
    return nodes


def test_a_sweep_runs_on_a_two_node_cluster_started_with_ray_start(cluster, tmp_path):
    nodes = cluster["nodes"]
    assert len(nodes) == 2, f"two alive nodes before the sweep, not {nodes}:\n{cluster['head_out']}"
    assert [n["cpus"] for n in nodes] == [1.0, 1.0], nodes
    out = tmp_path / "sweep"
    env = _env(cluster["home"], str(cluster["temp_dir"]), token=True)
    done = _sweep(cluster["address"], out, env)
    assert done.returncode == 0, done.stderr
    assert "2/2 builds succeeded" in done.stdout, done.stdout
    rows = _rows(out / "sweep.csv")
    assert sorted(r["friction"] for r in rows) == FRICTIONS
    for row in rows:
        assert (row["structure"], row["size"]) == ("pyramid-even", "layers=1"), row
        assert row["success"] == "true" and row["failure_reason"] == "", row
        assert row["bricks_placed"] == row["bricks_total"] == "2", row
    assert len(list((out / "runs").glob("*.json"))) == 2
    assert (out / "sweep.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # One CPU a node and two builds at once: each node ran one of them.
    # the job runner's Ray task, jobs/runner.py's _call, runs each build (sweep/runs.py's run_one)
    ran_on = _nodes_that_ran(cluster["temp_dir"] / "session_latest" / "logs", "_call")
    assert ran_on == {n["id"] for n in nodes}, (ran_on, nodes)


@pytest.fixture(scope="module")
def tokenless(cluster, tmp_path_factory):
    """The same sweep from a client elsewhere, with neither the token nor RAY_AUTH_MODE (about
    20 s: Ray retries, then gives up), its output folder and how long it took."""
    out = tmp_path_factory.mktemp("tokenless") / "sweep"
    elsewhere = tmp_path_factory.mktemp("client-home")
    start = time.monotonic()
    done = _sweep(cluster["address"], out, _env(elsewhere, str(cluster["temp_dir"]), token=False))
    return done, out, time.monotonic() - start


def test_a_client_without_token_mode_is_told_to_set_it(cluster, tokenless):
    done, out, took = tokenless
    assert done.returncode == 1, (done.returncode, done.stderr)
    assert "Traceback" not in done.stderr and "Traceback" not in done.stdout
    ours = [ln for ln in done.stderr.splitlines() if ln.startswith("pyramid-sim:")]
    assert len(ours) == 1, done.stderr
    assert ours[0] == done.stderr.strip().splitlines()[-1], done.stderr  # the last word
    assert ours[0].startswith(
        f"pyramid-sim: failed: cannot connect to the Ray cluster at {cluster['address']} "
    )
    assert "set RAY_AUTH_MODE=token" in ours[0] and "~/.ray/auth_token" in ours[0]
    assert done.stdout == ""
    # Nothing half-written: no table, no map, no runs.
    assert not (out / "sweep.csv").exists()
    assert not (out / "sweep.png").exists() and not (out / "runs").exists()
    assert took < 120, f"the refusal took {took:.0f} s"


def test_a_client_without_token_mode_gets_only_that_line(tokenless):
    """Ray's core logs a refused connection once a second on stderr; the sweep holds those
    lines back, so the user reads one line."""
    done, _, _ = tokenless
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
