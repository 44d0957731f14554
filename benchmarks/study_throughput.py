#!/usr/bin/env python3
"""Study machinery against plain runs (docs/STUDY.md, "Measurements"), each figure a ratio to a
reference measured in the same run:

1. the batch call: N short runs by vcontact.batch.run_batch on one thread, against the same runs
   one by one through Scenario.from_json(...).run() (the series handed to Python);
2. runs per second of a study on a LocalCluster of 1 and 2 workers, and in one process
   (--workers 0, 1 thread), for runs of about RUN_MS;
3. the study machinery's overhead per run: (study wall time × workers − the runs' own wall
   time) / runs, the cluster's start (a fixed cost) left out and given apart; as a share of a
   50 ms run;
4. the scheduler's cost per chunk: no-op tasks through the same client, per task.

Usage: PYTHONPATH=build/python /usr/bin/python3 benchmarks/study_throughput.py [--runs N]
"""

import argparse
import json
import os
import sys
import tempfile
import time

import numpy as np

import vcontact
from vcontact import batch
from vcontact.study import Study
from vcontact.study.runner import connect, run_study

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BALL_DROP = os.path.join(ROOT, "assets", "scenarios", "ball_drop.json")


def inline_ball_drop(folder):
    with open(BALL_DROP, encoding="utf-8") as f:
        doc = json.load(f)
    with open(os.path.join(ROOT, "assets", "scenarios", "steel_on_aluminium.model.json"),
              encoding="utf-8") as f:
        doc["models"] = {"steel": json.load(f)}
    doc["pairs"][0]["model"] = "steel"
    path = os.path.join(folder, "ball_drop.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    return path


def batch_call(scenario, n, duration):
    overrides = [{"bodies.ball.pose.z": 0.0105 + 1e-5 * k, "duration": duration}
                 for k in range(n)]
    t0 = time.perf_counter()
    results = batch.run_batch(scenario, overrides, threads=1)
    t_batch = time.perf_counter() - t0
    base = json.load(open(scenario, encoding="utf-8"))
    t0 = time.perf_counter()
    for o in overrides:
        doc = json.loads(json.dumps(base))
        for path, value in o.items():
            batch.set_path(doc, path, value)
        vcontact.Scenario.from_json(json.dumps(doc), "one", os.path.dirname(scenario)).run()
    t_single = time.perf_counter() - t0
    inside = sum(r["wall_time"] for r in results)
    return {"runs": n, "batch_s": t_batch, "one_by_one_s": t_single,
            "runs_own_wall_s": inside,
            "batch_per_run_overhead_ms": 1e3 * (t_batch - inside) / n,
            "one_by_one_over_batch": t_single / t_batch}


def study_doc(scenario, runs, duration):
    return {"format": "vcontact.study/1", "scenario": scenario,
            "set": {"duration": duration, "output_rate": 1000},
            "parameters": [{"name": "z0", "path": "bodies.ball.pose.z",
                            "uniform": {"low": 0.0102, "high": 0.0110}}],
            "count": runs, "seed": 1, "chunk_size": 10,
            "outputs": [{"name": "z_end", "quantity": "bodies.ball.final.z"},
                        {"name": "f", "quantity": "pairs.ball-plate.peak_f_n"}]}


def study_rate(folder, scenario, runs, duration, workers, threads=1):
    path = os.path.join(folder, f"s_{workers}_{time.monotonic_ns()}.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(study_doc(scenario, runs, duration), f)
    study = Study(path)
    out = path + ".out"
    client = cluster = None
    startup = 0.0
    if workers:
        t0 = time.perf_counter()
        client, cluster = connect(None, workers)
        client.wait_for_workers(workers)
        startup = time.perf_counter() - t0
    workers_cpu0 = sum(client.run(time.process_time).values()) if client else 0.0
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    try:
        workers_cpu = 0.0
        run_study(study, out, workers=workers, quiet=True, threads=threads, log=lambda s: None,
                  client=client)
        cpu = time.process_time() - cpu0
        if client:
            workers_cpu = sum(client.run(time.process_time).values()) - workers_cpu0
    finally:
        if client is not None:
            client.close()
            cluster.close()
    wall = time.perf_counter() - t0
    own = own_cpu = 0.0
    for name in os.listdir(os.path.join(out, "chunks")):
        with open(os.path.join(out, "chunks", name), encoding="utf-8") as f:
            rows = json.load(f)["rows"]
        own += sum(r["wall_time"] for r in rows)
        own_cpu += sum(r["cpu_time"] for r in rows)
    # CPU seconds of everything but the runs themselves (client, scheduler, workers' Python,
    # merge, report) over the runs' own CPU: independent of what else loads the machine.
    machinery_cpu = cpu + workers_cpu - own_cpu
    return {"workers": workers, "runs": runs, "cluster_start_s": startup, "wall_s": wall,
            "runs_per_s": runs / wall, "run_ms": 1e3 * own / runs, "own_s": own,
            "overhead_ms_per_run": 1e3 * (wall * max(1, workers) - own) / runs,
            "run_cpu_ms": 1e3 * own_cpu / runs,
            "machinery_cpu_ms_per_run": 1e3 * machinery_cpu / runs,
            "machinery_cpu_share": machinery_cpu / own_cpu}


def scheduler_cost(tasks):
    client, cluster = connect(None, 1)
    try:
        client.submit(lambda: 0).result()  # the worker is up
        t0 = time.perf_counter()
        futures = client.map(lambda k: k, range(tasks), pure=False)
        client.gather(futures)
        return {"tasks": tasks, "ms_per_task": 1e3 * (time.perf_counter() - t0) / tasks}
    finally:
        client.close()
        cluster.close()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=120)
    ap.add_argument("--duration", type=float, default=1.5,
                    help="simulated s of a run: ball_drop, 1.5 s is ~50 ms of wall time here")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="vcontact-bench-") as folder:
        scenario = inline_ball_drop(folder)
        print(json.dumps({"batch_call": batch_call(scenario, 200, 0.02)}), flush=True)
        here = study_rate(folder, scenario, args.runs, args.duration, 0)
        print(json.dumps({"in_process": here}), flush=True)
        for w in (1, 2):
            r = study_rate(folder, scenario, args.runs, args.duration, w)
            r["overhead_per_run"] = (r["wall_s"] * w - r["own_s"]) / r["own_s"]
            r["overhead_for_50ms_runs"] = r["overhead_ms_per_run"] / 50.0
            print(json.dumps({"local_cluster": r}), flush=True)
        print(json.dumps({"scheduler": scheduler_cost(500)}), flush=True)


if __name__ == "__main__":
    sys.exit(main())
