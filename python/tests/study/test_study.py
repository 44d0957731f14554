"""Studies (docs/STUDY.md): the batch call against single runs, paths and expressions, the study
file's errors, a real Dask cluster on 127.0.0.1 losing a worker, an interrupted local study
resumed, and a study file changed under a resumed run."""

import csv
import json
import os
import signal
import socket
import subprocess

import numpy as np
import pytest

import vcontact
from vcontact import batch
from vcontact.study import Expression, ExpressionError, Study, StudyError
from vcontact.study.report import first_order_index, wilson

from conftest import (BALL_DROP, dask_command, free_port, run_study, small_study,
                      wait_for, worker_env)



def table(out):
    """results.csv as a list of rows, without the wall time (the one column that differs)."""
    with open(os.path.join(out, "results.csv"), encoding="utf-8") as f:
        rows = list(csv.reader(f))
    wall = rows[0].index("wall_time_s")
    return [r[:wall] + r[wall + 1:] for r in rows]


# --- the batch call ------------------------------------------------------------------------

def test_a_batch_gives_the_figures_of_single_runs_to_the_bit(inline_ball_drop):
    heights = [0.0105, 0.012, 0.015]
    overrides = [{"bodies.ball.pose.z": z, "duration": 0.08} for z in heights]
    results = batch.run_batch(inline_ball_drop, overrides, threads=2,
                              events=[{"name": "touch", "body": "ball", "axis": 2,
                                       "level": 0.01, "below": True}])
    assert len(results) == 3
    base = json.loads(inline_ball_drop.read_text())
    for z, r in zip(heights, results):
        doc = json.loads(json.dumps(base))
        batch.set_path(doc, "bodies.ball.pose.z", z)
        batch.set_path(doc, "duration", 0.08)
        single = vcontact.Scenario.from_json(json.dumps(doc), "single",
                                             str(inline_ball_drop.parent)).run()
        ball, pair = single["bodies"]["ball"], single["pairs"]["ball-plate"]
        assert r["status"] == "completed" and r["message"] == ""
        np.testing.assert_array_equal(r["bodies"]["ball"]["final_p"], ball["p"][-1])
        np.testing.assert_array_equal(r["bodies"]["ball"]["min_p"], ball["p"].min(axis=0))
        assert r["pairs"]["ball-plate"]["peak_f_n"] == pair["f_n"].max()
        impulses = [i["normal_impulse_Ns"] for i in single["summary"]["impacts"]]
        np.testing.assert_array_equal(r["pairs"]["ball-plate"]["impacts"]["normal_impulse_Ns"],
                                      impulses)
        # The crossing lies between the two output samples around it.
        k = np.flatnonzero(ball["p"][:, 2] < 0.01)[0]
        assert ball["t"][k - 1] <= r["events"]["touch"] <= ball["t"][k]
        assert r["wall_time"] > 0


def test_a_discrete_batch_gives_the_rebound_each_impact_was_predicted(inline_ball_drop):
    """The impacts' predicted_rebound_m_s (the discrete stepper's decision, docs/DISCRETE.md
    §5) are summary.json's, to the bit; the ball's bounces rebound at 0.1-0.26 m/s, above the
    default threshold, so every one was predicted above it."""
    doc = json.loads(inline_ball_drop.read_text())
    doc["integrator"] = "discrete"
    doc["duration"] = 0.2
    discrete = inline_ball_drop.parent / "ball_drop_discrete.json"
    discrete.write_text(json.dumps(doc))
    r = batch.run_batch(discrete, [{}], threads=1)[0]
    single = vcontact.Scenario.from_json(json.dumps(doc), "single",
                                         str(inline_ball_drop.parent)).run()
    predicted = [i["predicted_rebound_m_s"] for i in single["summary"]["impacts"]]
    assert len(predicted) >= 3
    assert all(p >= 0.05 for p in predicted)
    np.testing.assert_array_equal(r["pairs"]["ball-plate"]["impacts"]["predicted_rebound_m_s"],
                                  predicted)


def test_a_run_that_fails_or_stops_is_a_result_not_an_exception(inline_ball_drop):
    results = batch.run_batch(inline_ball_drop, [
        {"models.steel.effects.stiffness.kv": -1.0},   # refused by the model's bounds
        {"models.steel.effects.stiffness.kv": 1e3},    # sinks: penetration beyond bound
        {"duration": 0.01}])
    assert results[0]["status"] == "error"
    assert "effects.stiffness" in results[0]["message"] and "run 0" in results[0]["message"]
    assert results[1]["status"] == "stopped"
    assert results[1]["stop_cause"] == "penetration_beyond_bound"
    assert results[1]["stop_time"] < 0.3
    assert results[2]["status"] == "completed"


def test_paths_reach_poses_shapes_lists_and_named_elements():
    doc = {"bodies": [{"name": "peg", "pose": "0,0,0.01", "shape": "meshes/peg.stl@mm"},
                      {"name": "ball", "shape": "cylinder:0.01,0.02", "pose": [1, 2, 3]}],
           "loads": [{"name": "drive", "stiffness": [200, 200, 2000]}],
           "pairs": [{"a": "peg", "b": "ball", "max_patches": 4}]}
    batch.set_path(doc, "bodies.peg.pose.roll", 5)
    batch.set_path(doc, "bodies.peg.shape.scale", 0.00101)
    batch.set_path(doc, "bodies.ball.shape.length", 0.03)
    batch.set_path(doc, "bodies[1].pose[2]", 4)
    batch.set_path(doc, "loads.drive.stiffness.2", 1000)
    batch.set_path(doc, "pairs.peg-ball.max_patches", 2)
    assert doc["bodies"][0]["pose"] == [0, 0, 0.01, 5.0, 0, 0]
    assert doc["bodies"][0]["shape"] == "meshes/peg.stl@0.00101"
    assert doc["bodies"][1]["shape"] == "cylinder:0.01,0.03"
    assert doc["bodies"][1]["pose"] == [1, 2, 4.0, 0, 0, 0]
    assert doc["loads"][0]["stiffness"] == [200, 200, 1000.0]
    assert doc["pairs"][0]["max_patches"] == 2.0
    assert batch.get_path(doc, "bodies.peg.pose.roll") == 5.0
    with pytest.raises(ValueError, match=r"no element named 'pge' \(there are: peg, ball\)"):
        batch.set_path(doc, "bodies.pge.pose.x", 1)
    with pytest.raises(ValueError, match="a cylinder shape has radius, length"):
        batch.set_path(doc, "bodies.ball.shape.scale", 1)


def test_expressions_are_arithmetic_only():
    e = Expression("2 * x if x > 1 else -x + max(x, y) ** 2", {"x", "y"}, "o")
    assert e({"x": 3.0, "y": 0.0}) == 6.0 and e({"x": 0.5, "y": 2.0}) == 3.5
    assert Expression("x / 0", {"x"}, "o")({"x": 1.0}) == float("inf")
    assert Expression("isnan(x) and not y", {"x", "y"}, "o")({"x": float("nan"),
                                                                "y": 0.0}) == 1.0
    for text, why in [("__import__('os').system('true')", "calls only"),
                      ("x.real", "Attribute is not allowed"), ("'a'", "only numbers"),
                      ("[x for x in y]", "ListComp is not allowed"), ("z + 1", "no output")]:
        with pytest.raises(ExpressionError, match=why):
            Expression(text, {"x", "y"}, "o")


def test_wilson_interval_and_first_order_index_against_closed_forms():
    # Wilson (1927) for 0 of 10 at 95 %: [0, z^2 / (n + z^2)] = [0, 0.2775].
    lo, hi = wilson(0, 10)
    assert lo == 0.0 and hi == pytest.approx(1.959963985**2 / (10 + 1.959963985**2), rel=1e-12)
    # Y = X1 + 0.5 X2 with X1, X2 independent uniform: S1 = 1/1.25 = 0.8, S2 = 0.2. 8 bins
    # leave 1/64 of each variable's own variance inside the bins (width 1/8: the within-bin
    # variance is (1/8)^2 of the whole): S1 estimated ~0.8 (1 - 1/64), with sampling error
    # ~1/sqrt(N) = 0.01 at N = 10^4; 0.03 allows both.
    rng = np.random.default_rng(3)
    x1, x2 = rng.random(10_000), rng.random(10_000)
    y = x1 + 0.5 * x2
    assert first_order_index(x1, y) == pytest.approx(0.8, abs=0.03)
    assert first_order_index(x2, y) == pytest.approx(0.2, abs=0.03)
    assert first_order_index(rng.random(10_000), y) < 0.01  # an unrelated input


# --- the study file --------------------------------------------------------------------------

def test_the_design_is_seeded_and_within_its_distributions(tmp_path, inline_ball_drop):
    path = small_study(tmp_path, inline_ball_drop, count=16)
    s, again = Study(path), Study(path)
    assert s.runs == 32 and s.names == ["z0", "a"]
    np.testing.assert_array_equal(s.rows, again.rows)
    assert np.all((s.rows[:, 0] >= 0.0102) & (s.rows[:, 0] <= 0.0110))
    # The list is the outer factor: 16 sampled points with a = 0.5, then the same 16 with 2.
    np.testing.assert_array_equal(s.rows[:16, 0], s.rows[16:, 0])
    assert set(s.rows[:16, 1]) == {0.5} and set(s.rows[16:, 1]) == {2.0}
    # A Sobol sample of 16 puts exactly one point in each sixteenth of the range.
    cells = np.floor((s.rows[:16, 0] - 0.0102) / 0.0008 * 16)
    assert sorted(cells) == list(range(16))
    other = small_study(tmp_path, inline_ball_drop, name="other.json", count=16, seed=8)
    assert not np.array_equal(Study(other).rows, s.rows)


@pytest.mark.parametrize("change, message", [
    ({"parameters": [{"name": "z0", "path": "bodies.bal.pose.z", "uniform": {"low": 0,
                                                                             "high": 1}}]},
     r"parameters\[0\].path: path 'bodies.bal.pose.z' at bodies.bal: no element named 'bal' \(there are: "
     r"plate, ball\)"),
    ({"parameters": [{"name": "z0", "path": "bodies.ball.pose.z", "uniform": {"low": 1,
                                                                              "high": 1}}]},
     r"parameters\[0\].uniform: low \(1\) must be below high \(1\)"),
    ({"parameters": [{"name": "k", "path": "duration", "lognormal": {"median": 0.1,
                                                                     "sigma": -1}}]},
     r"parameters\[0\].lognormal.sigma: expected sigma \(of the log\) > 0"),
    ({"parameters": [{"name": "k", "path": "duration", "normal": {"mean": 0.1, "std": 0.01,
                                                                  "low": 1, "high": 2}}]},
     r"parameters\[0\].normal: \[1, 2\] holds no probability"),
    ({"outputs": [{"name": "f", "quantity": "pairs.ball-plate.peak_fn"}]},
     r"outputs\[0\].quantity: no quantity 'pairs.ball-plate.peak_fn' in a run of .*there are: "
     r".*pairs.ball-plate.peak_f_n"),
    ({"outputs": [{"name": "f", "expression": "g * 2"}]},
     r"outputs\[0\].expression: 'g \* 2': no output or parameter named 'g'"),
])
def test_a_bad_study_is_refused_naming_the_place(tmp_path, inline_ball_drop, change, message):
    path = small_study(tmp_path, inline_ball_drop, **change)
    with pytest.raises(StudyError, match=message):
        Study(path)
    out = tmp_path / "out"
    r = run_study(path, "--out", out, "--workers", "0")
    assert r.returncode == 2, r.stderr
    assert str(path) in r.stderr and not out.exists()  # nothing written


def test_an_unreachable_scheduler_is_named_within_the_timeout(tmp_path, inline_ball_drop):
    with socket.socket() as s:  # a port nothing listens on: bound, never listening
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
        path = small_study(tmp_path, inline_ball_drop)
        # The client gives up after its 5 s connect timeout; 60 s only bounds a hang.
        r = run_study(path, "--out", tmp_path / "out", "--scheduler", f"tcp://127.0.0.1:{port}",
                      timeout=60)
    assert r.returncode == 2
    assert f"--scheduler tcp://127.0.0.1:{port}: no Dask scheduler answered" in r.stderr


# --- running ---------------------------------------------------------------------------------

def test_a_study_in_one_process_gives_its_table_and_report(tmp_path, inline_ball_drop):
    path = small_study(tmp_path, inline_ball_drop, count=None,
                       parameters=[{"name": "mu", "path": "models.steel.effects.coulomb.mu",
                                    "values": [0.1, 0.3]}])
    out = tmp_path / "out"
    r = run_study(path, "--out", out, "--workers", "0", "--h5")
    assert r.returncode == 0, r.stderr
    rows = table(out)
    assert rows[0] == ["run", "seed", "mu", "z_end", "f_peak", "impacts", "t_touch", "bounced",
                       "status", "message"]
    body = rows[1:]
    assert [int(x[0]) for x in body] == list(range(2))  # two levels, no distribution
    # mu = 0.3 exceeds the model's stribeck mu_s = 0.2: that run is a row with the error.
    assert body[0][-2] == "completed" and body[1][-2] == "error"
    assert "mu_s" in body[1][-1]
    # Free fall of 5 mm to the plate: t = sqrt(2 h / g); the crossing is placed linearly
    # between samples 1 ms apart, off the parabola by at most g dt^2 / 8 / v = 4e-6 s.
    assert float(body[0][6]) == pytest.approx((2 * 0.005 / 9.81) ** 0.5, abs=1e-5)
    assert body[1][3] == "nan"  # no figure for the run that never ran
    import h5py
    with h5py.File(out / "results.h5") as f:
        assert f["mu"][1] == 0.3 and f["status"][1].decode() == "error"
    report = (out / "report.html").read_text()
    assert "Stopped and failed runs (1)" in report
    assert f"vcontact study {path} --run 1 --out {out}/run_1" in report
    # The command in the report reproduces the run alone: the same error for run 1, the
    # output of `simulate` for run 0.
    alone = run_study(path, "--run", 1, "--out", tmp_path / "alone1")
    assert alone.returncode == 2 and "mu_s" in alone.stderr
    alone = run_study(path, "--run", 0, "--out", tmp_path / "alone0")
    assert alone.returncode == 0, alone.stderr
    bodies = np.genfromtxt(tmp_path / "alone0" / "bodies.csv", delimiter=",", names=True,
                           dtype=None, encoding="utf-8")
    assert repr(float(bodies[bodies["body"] == "ball"]["z"][-1])) == body[0][3]


def chunk_files(out):
    d = out / "chunks"
    return sorted(p.name for p in d.glob("chunk_*.json")) if d.exists() else []


# Runs of ~20-60 ms each (ball_drop over 2 s: the ball bounces, then rests under dopri5's
# max_step), 24 runs in chunks of 2: long enough that a worker is killed while chunks remain.
SLOW = {"count": 12, "duration": 2.0, "chunk_size": 2}


def test_a_cluster_that_loses_a_worker_gives_the_whole_table(tmp_path, inline_ball_drop,
                                                             services):
    path = small_study(tmp_path, inline_ball_drop, **SLOW)
    reference = tmp_path / "reference"
    r = run_study(path, "--out", reference, "--workers", "0")
    assert r.returncode == 0, r.stderr
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = worker_env()
    services.start(dask_command("scheduler") + ["--host", "127.0.0.1", "--port", str(port),
                                                "--no-dashboard"], env=env)
    workers = [services.start(dask_command("worker") + [address, "--nthreads", "1",
                                                        "--no-nanny", "--no-dashboard",
                                                        "--host", "127.0.0.1"], env=env)
               for _ in range(2)]
    out = tmp_path / "cluster"
    study = services.start([*__import__("conftest").study_command(path, "--out", out,
                                                                  "--scheduler", address)],
                           env=env)
    wait_for(lambda: len(chunk_files(out)) >= 2 or study.poll() is not None,
             "the first chunks on the cluster")
    assert study.poll() is None, study.stderr.read().decode()
    assert len(chunk_files(out)) < 12  # chunks remain, some of them on the worker killed now
    os.kill(workers[1].pid, signal.SIGKILL)
    assert study.wait(timeout=600) == 0, study.stderr.read().decode()
    assert len(chunk_files(out)) == 12
    assert table(out) == table(reference)  # complete, and the same to the bit


def test_an_interrupted_study_resumes_without_rerunning_finished_chunks(tmp_path,
                                                                        inline_ball_drop,
                                                                        services):
    path = small_study(tmp_path, inline_ball_drop, **SLOW)
    out = tmp_path / "local"
    study = services.start(__import__("conftest").study_command(path, "--out", out,
                                                                "--workers", "1"),
                           env=worker_env())
    wait_for(lambda: len(chunk_files(out)) >= 2 or study.poll() is not None, "two chunks")
    os.kill(study.pid, signal.SIGINT)
    assert study.wait(timeout=120) == 130, study.stderr.read().decode()
    kept = {name: (out / "chunks" / name).stat().st_mtime_ns for name in chunk_files(out)}
    assert 2 <= len(kept) < 12
    r = run_study(path, "--out", out, "--workers", "1")
    assert r.returncode == 0, r.stderr
    assert f"{len(kept)} of 12 chunks already finished" in r.stderr
    for name, mtime in kept.items():  # kept, not run again
        assert (out / "chunks" / name).stat().st_mtime_ns == mtime
    reference = tmp_path / "reference"
    assert run_study(path, "--out", reference, "--workers", "0").returncode == 0
    assert table(out) == table(reference)


def test_a_changed_study_is_refused_on_resume(tmp_path, inline_ball_drop):
    path = small_study(tmp_path, inline_ball_drop, count=2)
    out = tmp_path / "out"
    assert run_study(path, "--out", out, "--workers", "0").returncode == 0
    before = (out / "results.csv").read_text()
    small_study(tmp_path, inline_ball_drop, count=2, seed=99)  # same file, another seed
    r = run_study(path, "--out", out, "--workers", "0")
    assert r.returncode == 2
    assert f"{out}: holds the results of another study" in r.stderr
    assert "refusing to mix" in r.stderr
    assert (out / "results.csv").read_text() == before


def test_the_command_documents_its_options():
    from conftest import BINARY
    r = subprocess.run([BINARY, "study", "--help"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0
    for option in ("--out", "--workers", "--scheduler", "--chunk-size", "--run", "--h5",
                   "docs/STUDY.md"):
        assert option in r.stdout
    r = subprocess.run([BINARY, "study", "x.json"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "--out is required" in r.stderr
