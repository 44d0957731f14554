"""Fit studies (docs/STUDY.md, "Fit studies"): the cross-validated trajectory fit of tosses the
engine made, sent part by part to a real Dask cluster on 127.0.0.1 and to a LocalCluster, is
`vcontact fit` in one process to the bit; a resumed study runs nothing again; a part that fails
is a row with its error; bad study files and bad --fold / --merge are refused."""

import csv
import json
import os
import shutil
import subprocess

import pytest

from conftest import BINARY, dask_command, free_port, run_study, worker_env
from tosses import make_tosses

TOSSES, FOLDS = 6, 3
# Small budgets: the test checks that the parts merge to the single-process fit, not the fit's
# quality (tests/validation/trajectory_fit_test.cpp holds that), so every part takes ~1 s.
BUDGET = {"global_evaluations": 8, "local_evaluations": 6, "polishes": 1}
OPTIONS = ["--folds", str(FOLDS), "--global-evaluations", "8", "--local-evaluations", "6",
           "--polishes", "1"]
TIMINGS = ("wall_s", "cpu_s")  # the only fields of fit.json that differ between two runs


@pytest.fixture(scope="module")
def tosses(tmp_path_factory):
    """The tosses, their start model, a fit study of them and `vcontact fit` of the same."""
    root = tmp_path_factory.mktemp("fit")
    make_tosses(BINARY, str(root / "tosses"), count=TOSSES)
    study = root / "fit.study.json"
    study.write_text(json.dumps({"format": "vcontact.study/1", "description": "engine tosses",
                                 "fit": {"datasets": "tosses",
                                         "model": "tosses/start.model.json",
                                         "folds": FOLDS, **BUDGET}}))
    reference = root / "reference"
    fit(root / "tosses", "--out", reference)
    return root, study, reference


def fit(*args, expect=0):
    r = subprocess.run([BINARY, "fit", *map(str, args[:1]), "--model",
                        os.path.join(str(args[0]) if os.path.isdir(str(args[0]))
                                     else os.path.dirname(str(args[0])), "start.model.json"),
                        *OPTIONS, *map(str, args[1:])], capture_output=True, text=True)
    assert r.returncode == expect, r.stderr
    return r


def fit_json(folder):
    with open(os.path.join(folder, "fit.json"), encoding="utf-8") as f:
        doc = json.load(f)
    for key in TIMINGS:
        doc.pop(key)
    return doc


def read(path):
    with open(path, "rb") as f:
        return f.read()


def assert_same_fit(merged, reference):
    """The merged fit is the single-process one: the held-out e_q of every trial and every
    fitted value equal as doubles, and model.json, trials.csv and fit.json (timings aside) the
    same bytes."""
    got, want = fit_json(merged), fit_json(reference)
    held = [t["e_q_held_out"] for t in got["trials"]]
    assert len(held) == TOSSES and all(isinstance(v, float) for v in held)  # every toss held out
    assert held == [t["e_q_held_out"] for t in want["trials"]]
    assert ([p["value"] for p in got["parameters"]]
            == [p["value"] for p in want["parameters"]])
    assert got == want
    for name in ("model.json", "trials.csv"):
        assert read(merged / name) == read(reference / name), name


def parts_table(out):
    with open(out / "parts.csv", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_a_fit_study_on_a_cluster_is_the_fit_of_one_process_to_the_bit(tosses, services,
                                                                        tmp_path):
    root, study, reference = tosses
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = worker_env()
    services.start(dask_command("scheduler") + ["--host", "127.0.0.1", "--port", str(port),
                                                "--no-dashboard"], env=env)
    for _ in range(2):
        services.start(dask_command("worker") + [address, "--nthreads", "1", "--no-nanny",
                                                 "--no-dashboard", "--host", "127.0.0.1"],
                       env=env)
    out = tmp_path / "cluster"
    r = run_study(study, "--out", out, "--scheduler", address)
    assert r.returncode == 0, r.stderr
    rows = parts_table(out)
    assert [row["part"] for row in rows] == ["all"] + [str(i) for i in range(FOLDS)]
    assert {row["status"] for row in rows} == {"completed"}
    assert_same_fit(out / "fit", reference)
    # Rerun: every part is kept, none runs again, the merge is the same.
    before = {p: read(p) for p in (out / "parts").iterdir()}
    r = run_study(study, "--out", out, "--workers", "0")
    assert r.returncode == 0, r.stderr
    assert f"{FOLDS + 1} of {FOLDS + 1} parts already finished, 0 to run" in r.stderr
    assert {p: read(p) for p in (out / "parts").iterdir()} == before
    assert_same_fit(out / "fit", reference)


def test_a_fit_study_on_a_local_cluster_resumes_a_lost_part(tosses, tmp_path):
    root, study, reference = tosses
    out = tmp_path / "local"
    r = run_study(study, "--out", out, "--workers", "2")
    assert r.returncode == 0, r.stderr
    assert_same_fit(out / "fit", reference)
    os.remove(out / "parts" / "part_1.json")  # as if the study had stopped before it
    shutil.rmtree(out / "fit")
    r = run_study(study, "--out", out, "--workers", "2")
    assert r.returncode == 0, r.stderr
    assert f"{FOLDS} of {FOLDS + 1} parts already finished, 1 to run" in r.stderr
    assert_same_fit(out / "fit", reference)


def test_a_part_that_fails_is_a_row_with_its_error_and_nothing_is_merged(tosses, tmp_path):
    root, _, _ = tosses
    data = tmp_path / "tosses"
    shutil.copytree(root / "tosses", data)
    with open(data / "toss4.csv", encoding="utf-8") as f:
        lines = f.read().splitlines()
    lines[3], lines[4] = lines[4], lines[3]  # time no longer increasing
    (data / "toss4.csv").write_text("\n".join(lines) + "\n")
    study = tmp_path / "broken.study.json"
    study.write_text(json.dumps({"format": "vcontact.study/1", "fit": {
        "datasets": "tosses", "model": "tosses/start.model.json", "folds": FOLDS, **BUDGET}}))
    out = tmp_path / "out"
    r = run_study(study, "--out", out, "--workers", "0")
    assert r.returncode == 1, r.stderr
    rows = parts_table(out)
    assert len(rows) == FOLDS + 1 and {row["status"] for row in rows} == {"error"}
    assert all("toss4" in row["message"] for row in rows), rows
    assert "not merged" in r.stderr and not (out / "fit").exists()
    assert not list((out / "parts").iterdir())


@pytest.mark.parametrize("fit_doc, message", [
    ({"model": "tosses/start.model.json"},
     r"fit.datasets: expected a dataset sidecar, a folder of them or a list file"),
    ({"datasets": "tosses", "model": "tosses/start.model.json", "starts": 3},
     r"fit.starts: unknown option \(expected one of: datasets, fix_plate, folds, "
     r"global_evaluations, h, integrator, local_evaluations, model, plate_offset, polishes\)"),
    ({"datasets": "tosses", "model": "tosses/start.model.json", "folds": 1},
     r"fit.folds: expected 0 \(none\) or k >= 2, got 1"),
    ({"datasets": "tosses", "model": "tosses/start.model.json", "folds": 7},
     r"fit.folds: 7 folds need as many trials; 6 datasets given"),
    ({"datasets": "nowhere", "model": "tosses/start.model.json"},
     r"fit.datasets: .*nowhere: no such dataset, folder or list"),
    ({"datasets": "tosses", "model": "none.json"}, r"fit.model: .*none.json: no such model"),
    ({"datasets": "tosses", "model": "tosses/start.model.json", "integrator": "euler"},
     r'fit.integrator: expected discrete \| dopri5 \| bdf, got "euler"'),
])
def test_a_bad_fit_study_is_refused_naming_the_place(tosses, tmp_path, fit_doc, message):
    root, _, _ = tosses
    shutil.copytree(root / "tosses", tmp_path / "tosses")
    study = tmp_path / "bad.study.json"
    study.write_text(json.dumps({"format": "vcontact.study/1", "fit": fit_doc}))
    out = tmp_path / "out"
    r = run_study(study, "--out", out, "--workers", "0")
    assert r.returncode == 2, r.stderr
    assert str(study) in r.stderr
    assert __import__("re").search(message, r.stderr), r.stderr
    assert not out.exists()  # nothing written


def test_options_of_run_studies_are_refused_by_a_fit_study(tosses, tmp_path):
    _, study, _ = tosses
    for extra, message in ((["--chunk-size", "2"], "--chunk-size: a fit study runs one part"),
                           (["--run", "0"], "--run: not an option of a fit study")):
        r = run_study(study, "--out", tmp_path / "out", "--workers", "0", *extra)
        assert r.returncode == 2 and message in r.stderr, r.stderr
    assert not (tmp_path / "out").exists()


def test_fold_and_merge_refuse_what_is_not_a_fold_of_this_fit(tosses, tmp_path):
    root, _, _ = tosses
    data = root / "tosses"
    for args, message in (
            (["--fold", str(FOLDS)], f"--fold: fold {FOLDS} of a {FOLDS}-fold cross-validation"),
            (["--fold", "-1"], '--fold: expected "all" or a fold number 0..k-1, got "-1"'),
            (["--fold", "0", "--merge", "x.json"], "--merge: excludes --fold")):
        r = fit(data, "--out", tmp_path / "bad", *args, expect=2)
        assert message in r.stderr, r.stderr
    r = fit(data / "toss0.json", "--out", tmp_path / "bad", "--fold", "0", expect=2)
    assert f"--folds: {FOLDS} folds need as many trials; 1 given" in r.stderr, r.stderr
    for part in ("all", "0"):
        fit(data, "--out", tmp_path / part, "--fold", part)
    r = fit(data, "--out", tmp_path / "bad", "--merge", tmp_path / "all" / "fold.json",
            tmp_path / "0" / "fold.json", expect=2)
    assert "--merge: fold 1 is missing" in r.stderr, r.stderr
    r = fit(data, "--out", tmp_path / "bad", "--merge", tmp_path / "0" / "fold.json",
            tmp_path / "0" / "fold.json", expect=2)
    assert "a second part of fold 0" in r.stderr, r.stderr
    r = subprocess.run([BINARY, "fit", str(data), "--model", str(data / "start.model.json"),
                        "--folds", str(FOLDS), "--out", str(tmp_path / "bad"), "--merge",
                        str(tmp_path / "all" / "fold.json")], capture_output=True, text=True)
    assert r.returncode == 2 and "made with other options than this fit's" in r.stderr, r.stderr
    assert not (tmp_path / "bad").exists()
