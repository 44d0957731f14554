"""Shared fixtures of the study tests: a tiny study of ball_drop, the command to run it, and the
scaffolding of the cluster tests (a scheduler and workers on 127.0.0.1, started and stopped by
the test)."""

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

import pytest

import vcontact

SOURCE = os.environ.get("VCONTACT_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", "..", ".."))
ASSETS = os.path.join(SOURCE, "assets")
BINARY = os.environ.get("VCONTACT_BINARY", os.path.join(SOURCE, "build", "bin", "vcontact"))
BALL_DROP = os.path.join(ASSETS, "scenarios", "ball_drop.json")


def small_study(tmp_path, scenario, name="ball.study.json", count=12, duration=0.05,
                chunk_size=2,
                **changes):
    """ball_drop shortened to `duration`, the drop height sampled and the damping listed,
    a few outputs: a study of `count` runs that costs milliseconds each."""
    doc = {
        "format": "vcontact.study/1",
        "description": "ball_drop, height and stiffness sampled",
        "scenario": os.path.relpath(scenario, tmp_path),
        "set": {"duration": duration, "output_rate": 1000},
        "parameters": [
            {"name": "z0", "path": "bodies.ball.pose.z", "uniform": {"low": 0.0102,
                                                                      "high": 0.0110}},
            {"name": "a", "path": "models.steel.effects.damping.a", "values": [0.5, 2.0]},
        ],
        "count": count,
        "seed": 7,
        "chunk_size": chunk_size,
        "outputs": [
            {"name": "z_end", "quantity": "bodies.ball.final.z"},
            {"name": "f_peak", "quantity": "pairs.ball-plate.peak_f_n"},
            {"name": "impacts", "quantity": "pairs.ball-plate.impacts"},
            {"name": "t_touch", "crossing": {"body": "ball", "coordinate": "z", "below": 0.01}},
            {"name": "bounced", "expression": "impacts >= 2"},
        ],
    }
    doc.update(changes)
    if doc["count"] is None:
        del doc["count"]
    path = tmp_path / name
    path.write_text(json.dumps(doc, indent=1))
    return path


@pytest.fixture
def inline_ball_drop(tmp_path):
    """ball_drop with its model inline (so that a study can vary mu), next to the test's files;
    the model file's content is copied, the plate and ball unchanged."""
    with open(BALL_DROP, encoding="utf-8") as f:
        doc = json.load(f)
    with open(os.path.join(ASSETS, "scenarios", "steel_on_aluminium.model.json"),
              encoding="utf-8") as f:
        model = json.load(f)
    doc["models"] = {"steel": model}
    doc["pairs"][0]["model"] = "steel"
    path = tmp_path / "ball_drop.json"
    path.write_text(json.dumps(doc, indent=1))
    return path


def study_command(*args):
    return [BINARY, "study", *map(str, args)]


def run_study(*args, timeout=600, **kw):
    env = dict(os.environ)
    env.pop("CI", None)
    return subprocess.run(study_command(*args), capture_output=True, text=True,
                          timeout=timeout, env=env, **kw)


def dask_command(which):
    """Dask's own command (`dask scheduler`, `dask worker`), or its module where the `dask`
    entry point is missing."""
    exe = shutil.which("dask")
    if exe:
        return [exe, which]
    return [sys.executable, "-m", f"distributed.cli.dask_{which}"]


POLL_S = 0.05  # how often a test looks for a chunk file or a process's end


def wait_for(predicate, what, limit_s=300):
    """Polls until predicate() holds; fails naming `what` after limit_s (a hang, not a timing
    assertion: the tests never depend on how fast a run is)."""
    end = time.monotonic() + limit_s
    while not predicate():
        if time.monotonic() > end:
            pytest.fail(f"waited {limit_s} s for {what}")
        time.sleep(POLL_S)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Services:
    """Processes a test starts, each in its own session, all stopped at the end, even when the
    test fails."""

    def __init__(self):
        self.procs = []

    def start(self, command, **kw):
        p = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             start_new_session=True, **kw)
        self.procs.append(p)
        return p

    def stop(self):
        for p in self.procs:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
        for p in self.procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()


@pytest.fixture
def services():
    s = Services()
    yield s
    s.stop()


def worker_env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([os.path.dirname(os.path.dirname(vcontact.__file__)),
                                         env.get("PYTHONPATH", "")])
    return env
