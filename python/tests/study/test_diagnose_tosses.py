"""`vcontact diagnose` on a folder of dynamic datasets (docs/DIAGNOSIS.md, "Trajectory
diagnosis"): tosses the engine made with damping, diagnosed from a start without it, give the
verdict damping and its fit; a diagnosis without cross-validation, or iterated, is refused."""

import csv
import json
import os
import subprocess

from conftest import BINARY
from tosses import make_tosses

OPTIONS = ["--global-evaluations", "8", "--local-evaluations", "6",
           "--polishes", "1", "--fix-plate"]
# The truth of tosses.py without its damping, the rest held at the truth's values (a search
# over mu would reach the sticking tosses that cost tens of times more to simulate).
START = {"format": "vcontact.model/1",
         "effects": {"stiffness": {"kv": 2e6}, "coulomb": {"mu": 0.1}},
         "fixed": ["stiffness.kv", "coulomb.mu", "coulomb.v_s"]}
CANDIDATES = {"format": "vcontact.candidates/1", "candidates": {"viscous": {}, "damping": {}}}


def diagnose(folder, out, folds=2, extra=()):
    return subprocess.run([BINARY, "diagnose", str(folder), "--model",
                           str(folder.parent / "start.json"), "--candidates",
                           str(folder.parent / "candidates.json"), *OPTIONS, "--folds",
                           str(folds), *extra, "--out", str(out)], capture_output=True, text=True)


def test_damping_hidden_from_the_start_is_the_verdict(tmp_path):
    folder = tmp_path / "tosses"
    make_tosses(BINARY, str(folder), count=4)
    (tmp_path / "start.json").write_text(json.dumps(START))
    (tmp_path / "candidates.json").write_text(json.dumps(CANDIDATES))
    r = diagnose(folder, tmp_path / "out")
    assert r.returncode == 0, r.stderr
    assert "verdict: damping" in r.stdout, r.stdout
    with open(tmp_path / "out" / "diagnosis.json", encoding="utf-8") as f:
        d = json.load(f)
    assert d["verdict"] == "damping"
    assert d["folds"] == 2 and d["trials_count"] == 4
    best = d["ranking"][0]
    assert best["effect"] == "damping" and best["accepted"]
    assert best["mean_e_q_held_out"] < d["baseline"]["mean_e_q_held_out"]
    assert best["mean_change"] < -2 * best["change_std_error"]
    assert not d["ranking"][1]["accepted"] and d["ranking"][1]["rejected"]
    with open(tmp_path / "out" / "model.json", encoding="utf-8") as f:
        assert "damping" in json.load(f)["effects"]
    with open(tmp_path / "out" / "trials.csv", encoding="utf-8") as f:
        assert len(list(csv.DictReader(f))) == 4
    with open(tmp_path / "out" / "report.html", encoding="utf-8") as f:
        assert "verdict: damping" in f.read()


def test_a_diagnosis_without_cross_validation_is_refused(tmp_path):
    folder = tmp_path / "tosses"
    make_tosses(BINARY, str(folder), count=2, duration=0.1)
    (tmp_path / "start.json").write_text(json.dumps(START))
    (tmp_path / "candidates.json").write_text(json.dumps(CANDIDATES))
    r = diagnose(folder, tmp_path / "out", folds=0)
    assert r.returncode == 2, r.stderr
    assert "--folds" in r.stderr and "held-out" in r.stderr, r.stderr
    assert not os.path.exists(tmp_path / "out" / "diagnosis.json")
    r = diagnose(folder, tmp_path / "out", extra=["--iterate"])
    assert r.returncode == 2, r.stderr
    assert "--iterate" in r.stderr and "kinematic" in r.stderr, r.stderr
    assert not os.path.exists(tmp_path / "out" / "diagnosis.json")
