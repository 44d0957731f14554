"""Studies: sweeps and Monte Carlo over a scenario's parameters, in chunks on Dask (a
LocalCluster by default, or a running scheduler), resumable, merged into one table and a report
(docs/STUDY.md). `python3 -m vcontact.study STUDY.json --out DIR` is `vcontact study`."""

from .expr import Expression, ExpressionError
from .runner import merge, run_study
from .spec import Study, StudyError

__all__ = ["Study", "StudyError", "Expression", "ExpressionError", "run_study", "merge",
           "run_one"]


def run_one(study, run, out):
    """Runs one run of the study alone with the full output of `vcontact simulate` in `out`
    (CSVs, summary.json), and the run's scenario as out/scenario.json (its relative paths are
    the base scenario's, resolved against its folder)."""
    import json
    import os

    from .. import Scenario
    from .spec import scenario_of
    if not 0 <= run < study.runs:
        raise StudyError(f"--run {run}: the study has runs 0 to {study.runs - 1}")
    doc = scenario_of(study.task_spec(), study.values_of(run))
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "scenario.json"), "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=2)
    s = Scenario.from_json(json.dumps(doc), f"{study.scenario_path} (run {run})",
                           study.scenario_dir)
    return s.run(out=out, check=False)
