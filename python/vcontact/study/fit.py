"""Fit studies: a cross-validated trajectory fit (`vcontact fit` over many dynamic datasets)
sent to the study's cluster (docs/STUDY.md, "Fit studies").

The k-fold cross-validated fit is k + 1 independent, deterministic fits: the one on all trials
and one per fold. Each is a Dask task that runs `vcontact fit ... --fold all|i` as a subprocess
on its worker and hands back the fold.json it wrote; the client writes each finished part
atomically (DIR/parts/part_all.json, part_0.json, ...) and, when every part is there, runs
`vcontact fit ... --merge PARTS` into DIR/fit: the same fit.json, model.json, trials.csv and
report.html as `vcontact fit` in one process gives, to the bit (the timings aside), whatever the
number of workers and the order they finish in.

    DIR/manifest.json        the study's identity (study file, model, every dataset's bytes)
    DIR/study.json           the study file as it was read
    DIR/parts/part_X.json    one per finished part, written atomically; kept on a rerun
    DIR/parts.csv            one row per part: status, message, wall time, host
    DIR/fit/                 the merged fit
"""

import csv
import hashlib
import io
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

from .runner import (INTERRUPT, MANIFEST_FORMAT, Progress, _number, _package_dir,
                     _write_atomic, connect, open_folder)
from .spec import FORMAT, StudyError, _canonical

INTEGRATORS = ("discrete", "dopri5", "bdf")
# key in the study's "fit": (the option of `vcontact fit`, the check, what the check expects)
OPTIONS = {
    "folds": ("--folds", lambda v: _int(v) and (v == 0 or v >= 2), "0 (none) or k >= 2"),
    "global_evaluations": ("--global-evaluations", lambda v: _int(v) and v >= 1,
                           "an integer >= 1"),
    "local_evaluations": ("--local-evaluations", lambda v: _int(v) and v >= 0,
                          "an integer >= 0"),
    "polishes": ("--polishes", lambda v: _int(v) and v >= 0, "an integer >= 0"),
    "h": ("--h", lambda v: _real(v) and v >= 0, "a length in m >= 0"),
    "plate_offset": ("--plate-offset", lambda v: _real(v), "a length in m"),
    "integrator": ("--integrator", lambda v: v in INTEGRATORS, " | ".join(INTEGRATORS)),
    "fix_plate": ("--fix-plate", lambda v: isinstance(v, bool), "true or false"),
}
DEFAULT_FOLDS = 5  # as `vcontact fit`


def _int(v):
    return isinstance(v, int) and not isinstance(v, bool)


def _real(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and v == v and abs(v) < 1e300


def binary():
    """The vcontact program the parts run: VCONTACT_BINARY (which `vcontact study` sets to
    itself), else `vcontact` on the PATH."""
    return os.environ.get("VCONTACT_BINARY") or shutil.which("vcontact") or "vcontact"


def _is_dataset(path):
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return False
    return isinstance(doc, dict) and doc.get("format") == "vcontact.dataset/1"


def _expand(args, where, fail):
    """Dataset sidecars from folders (their *.json sidecars, sorted by name), list files (.txt,
    .list: one path a line, relative to the list) and files, as `vcontact fit` expands them."""
    out = []
    for a in args:
        if os.path.isdir(a):
            found = sorted(os.path.join(a, n) for n in os.listdir(a)
                           if n.endswith(".json") and _is_dataset(os.path.join(a, n)))
            if not found:
                fail(where, f"{a}: a folder with no dataset sidecar (*.json)")
            out += found
        elif a.endswith((".txt", ".list")):
            try:
                with open(a, encoding="utf-8") as f:
                    lines = [s.strip() for s in f]
            except OSError as e:
                fail(where, f"{a}: cannot read the list of datasets ({e.strerror})")
            out += [os.path.join(os.path.dirname(a), s) for s in lines
                    if s and not s.startswith("#")]
        elif os.path.isfile(a):
            out.append(a)
        else:
            fail(where, f"{a}: no such dataset, folder or list")
    if not out:
        fail(where, "no dataset given")
    return out


class FitStudy:
    """A fit study file read and checked: the datasets (expanded, absolute), the start model,
    the options of `vcontact fit`, the parts ("all", then the folds) and the identity."""

    kind = "fit"

    def __init__(self, path, doc, text):
        self.path, self.doc, self.text = path, doc, text
        self.dir = os.path.dirname(os.path.abspath(path))
        allowed = {"format", "description", "fit"}
        for key in doc:
            if key not in allowed:
                self.fail(key, "unknown key in a fit study (expected one of: "
                          f"{', '.join(sorted(allowed))})")
        if doc.get("format") != FORMAT:
            self.fail("format", f'expected "{FORMAT}"')
        self.description = doc.get("description", "")
        fit = doc["fit"]
        if not isinstance(fit, dict):
            self.fail("fit", "expected an object with datasets, model and the fit's options")
        known = {"datasets", "model"} | set(OPTIONS)
        for key in fit:
            if key not in known:
                self.fail(f"fit.{key}", f"unknown option (expected one of: "
                          f"{', '.join(sorted(known))})")
        self.datasets = self._read_datasets(fit.get("datasets"))
        self.model = self._read_model(fit.get("model"))
        self.options = {}
        for key, (_, ok, expected) in OPTIONS.items():
            if key in fit:
                if not ok(fit[key]):
                    self.fail(f"fit.{key}", f"expected {expected}, got {json.dumps(fit[key])}")
                self.options[key] = fit[key]
        self.folds = self.options.get("folds", DEFAULT_FOLDS)
        if self.folds > len(self.datasets):
            n = len(self.datasets)
            self.fail("fit.folds", f"{self.folds} folds need as many trials; {n} "
                      f"dataset{'' if n == 1 else 's'} given")
        self.parts = ["all"] + [str(i) for i in range(self.folds)]
        self.identity = self._identity()

    def fail(self, where, message):
        raise StudyError(f"{self.path}: {where}: {message}")

    def _resolve(self, p):
        return os.path.normpath(os.path.join(self.dir, p))

    def _read_datasets(self, v):
        if isinstance(v, str):
            v = [v]
        if not isinstance(v, list) or not v or not all(isinstance(s, str) for s in v):
            self.fail("fit.datasets", "expected a dataset sidecar, a folder of them or a list "
                      "file (.txt), or a list of these, relative to the study file")
        return _expand([self._resolve(s) for s in v], "fit.datasets", self.fail)

    def _read_model(self, v):
        if not isinstance(v, str):
            self.fail("fit.model", "expected the start model's path (vcontact.model/1, "
                      "relative to the study file)")
        path = self._resolve(v)
        if not os.path.isfile(path):
            self.fail("fit.model", f"{path}: no such model file")
        return path

    def _identity(self):
        """A digest of everything that fixes the parts: the study, the model file and every
        dataset's sidecar and data bytes."""
        h = hashlib.sha256(_canonical(self.doc).encode())
        for path in [self.model] + self.datasets:
            h.update(path.encode())
            with open(path, "rb") as f:
                h.update(f.read())
            if path != self.model:
                with open(path, encoding="utf-8") as f:
                    data = json.load(f).get("data")
                if isinstance(data, str):
                    csv_path = os.path.join(os.path.dirname(path), data)
                    if os.path.isfile(csv_path):
                        with open(csv_path, "rb") as f:
                            h.update(f.read())
        return h.hexdigest()

    def fit_arguments(self):
        """The arguments of `vcontact fit` after the program's name, without --out and --fold:
        the same for every part, the merge and the single-process fit."""
        args = ["fit", *self.datasets, "--model", self.model]
        for key, (option, _, _) in OPTIONS.items():
            if key == "fix_plate":
                if self.options.get(key):
                    args.append(option)
            elif key in self.options:
                args += [option, repr(self.options[key])]
        return args

    def command(self, out, part=None):
        """The command line of one part alone (or, part None, the single-process fit)."""
        extra = ["--fold", part] if part is not None else []
        return [binary(), *self.fit_arguments(), "--out", out, *extra]


def _die_with_parent():
    """In the part's child process (Linux): killed when the worker that started it dies, so a
    killed worker leaves no fit running on (the scheduler reruns the part elsewhere)."""
    try:
        import ctypes
        PR_SET_PDEATHSIG = 1
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    except (OSError, AttributeError):
        pass  # not Linux: the orphan finishes its part and exits


def run_part(program, arguments, part, identity):
    """One part on whichever process runs it: `program fit ... --fold part` into a temporary
    folder; {identity, part, status, message, wall_time, host, fold (fold.json, or None)}.
    Pure but for the wall time and host: a part lost with its worker is run again elsewhere."""
    program = os.environ.get("VCONTACT_BINARY_ON_WORKER") or program
    host = f"{socket.gethostname()}:{os.getpid()}"  # the worker process that ran the part
    start = time.monotonic()
    record = {"identity": identity, "part": part, "host": host, "fold": None}
    if not (os.path.isfile(program) and os.access(program, os.X_OK)) and not shutil.which(program):
        record.update(status="error", wall_time=0.0,
                      message=f"no vcontact program {program} on {host} (install it at the same "
                              "path, or set VCONTACT_BINARY_ON_WORKER in the worker's "
                              "environment)")
        return record
    with tempfile.TemporaryDirectory(prefix="vcontact-fold-") as tmp:
        out = os.path.join(tmp, "out")
        r = subprocess.run([program, *arguments, "--out", out, "--fold", part],
                           capture_output=True, text=True, preexec_fn=_die_with_parent)
        record["wall_time"] = time.monotonic() - start
        if r.returncode != 0:
            lines = [s for s in r.stderr.splitlines() if s.strip()]
            record.update(status="error", message=(lines[-1] if lines else
                                                   f"vcontact fit exited {r.returncode}"))
            return record
        with open(os.path.join(out, "fold.json"), encoding="utf-8") as f:
            record["fold"] = json.load(f)
    record.update(status="completed", message="")
    return record


class PartsFolder:
    """The output folder of one fit study."""

    def __init__(self, out, study):
        self.out = os.fspath(out)
        self.study = study
        self.part_dir = os.path.join(self.out, "parts")

    def part_path(self, part):
        return os.path.join(self.part_dir, f"part_{part}.json")

    def open(self):
        """Creates the folder, or checks that it holds this study; returns the finished parts."""
        manifest = {"format": MANIFEST_FORMAT, "kind": "fit", "identity": self.study.identity,
                    "study": os.path.abspath(self.study.path),
                    "datasets": len(self.study.datasets), "parts": self.study.parts}
        open_folder(self.out, self.part_dir, self.study, manifest,
                    lambda old: f"{old.get('study')}): the study file, its model or a dataset "
                                "changed")
        parts = {p: self._read(p) for p in self.study.parts}
        return {p: doc for p, doc in parts.items() if doc is not None}

    def _read(self, part):
        try:
            with open(self.part_path(part), encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, ValueError):
            return None  # absent or unreadable: run it again
        return doc if doc.get("study_identity") == self.study.identity else None

    def write_part(self, record):
        """The part's fold.json, with the study's identity, status, wall time and host beside
        (the fit's --merge reads the fold's own fields and ignores these)."""
        doc = dict(record["fold"])
        doc.update({"study_identity": record["identity"], "status": record["status"],
                    "wall_time_s": record["wall_time"], "host": record["host"]})
        _write_atomic(self.part_path(record["part"]), json.dumps(doc, indent=1) + "\n")

    def write_table(self, rows):
        """parts.csv, one row per part in order, written atomically."""
        text = io.StringIO()
        w = csv.writer(text, lineterminator="\n")
        w.writerow(["part", "status", "message", "wall_time_s", "evaluations", "host"])
        for part in self.study.parts:
            r = rows[part]
            w.writerow([part, r["status"], r["message"], _number(r["wall_time"]),
                        r.get("evaluations", ""), r["host"]])
        _write_atomic(os.path.join(self.out, "parts.csv"), text.getvalue())


def _row(record):
    row = {k: record[k] for k in ("status", "message", "wall_time", "host")}
    if record.get("fold"):
        row["evaluations"] = record["fold"].get("evaluations", "")
    return row


def _run_parts_here(study, todo, on_done):
    args = study.fit_arguments()
    for part in todo:
        on_done(run_part(binary(), args, part, study.identity))


def _run_parts_dask(study, todo, on_done, client):
    """The parts as Dask tasks, the fit on all trials first (the longest); pure and named by the
    study's identity and the part, so a part whose worker died is run again elsewhere."""
    from distributed import as_completed
    args = study.fit_arguments()
    futures = [client.submit(run_part, binary(), args, part, study.identity,
                             key=f"vcontact-fold-{study.identity[:16]}-{part}", pure=True)
               for part in todo]
    for future in as_completed(futures):
        try:
            record = future.result()
        except Exception as e:  # the task itself failed, not the fit (which fails as a row)
            part = future.key.rpartition("-")[2]
            record = {"identity": study.identity, "part": part, "status": "error",
                      "wall_time": 0.0, "host": "", "fold": None,
                      "message": f"the task failed on the cluster: {type(e).__name__}: {e} (do "
                                 f"its workers import this vcontact? PYTHONPATH={_package_dir()})"}
        future.release()
        on_done(record)


def run_fit_study(study, out, workers=None, scheduler=None, quiet=False, log=None, client=None):
    """Runs (or resumes) the fit study into `out`, then merges the parts into out/fit.
    Returns {parts, completed, failed, resumed_parts, merged}; a failed part leaves the fit
    unmerged (the rerun of the same command runs only the parts missing)."""
    log = log or (lambda text: print(f"vcontact: {text}", file=sys.stderr))
    folder = PartsFolder(out, study)
    finished = folder.open()
    rows = {p: {"status": "completed", "message": "", "wall_time": r.get("wall_time_s", 0.0),
                "host": r.get("host", ""), "evaluations": r.get("evaluations", "")}
            for p, r in finished.items()}
    todo = [p for p in study.parts if p not in finished]
    if finished:
        log(f"resuming {out}: {len(finished)} of {len(study.parts)} parts already finished, "
            f"{len(todo)} to run")
    progress = Progress(len(study.parts), quiet, unit="parts")
    counts = {"done": len(finished), "failed": 0}

    def on_done(record):
        if record["status"] == "completed":
            folder.write_part(record)
        else:
            counts["failed"] += 1
        rows[record["part"]] = _row(record)
        counts["done"] += 1
        progress.update(counts["done"], counts["failed"])

    own, cluster = client is None, None
    start = time.monotonic()
    try:
        if todo and client is not None:
            _run_parts_dask(study, todo, on_done, client)
        elif todo and workers == 0 and not scheduler:
            _run_parts_here(study, todo, on_done)
        elif todo:
            client, cluster = connect(scheduler, min(workers or os.cpu_count() or 1, len(todo)))
            if INTERRUPT.is_set():
                raise KeyboardInterrupt
            _run_parts_dask(study, todo, on_done, client)
    finally:
        progress.finish()
        if own and client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    elapsed = time.monotonic() - start
    folder.write_table(rows)
    failed = [p for p in study.parts if rows[p]["status"] != "completed"]
    summary = {"parts": len(study.parts), "completed": len(study.parts) - len(failed),
               "failed": len(failed), "resumed_parts": len(finished), "merged": False}
    if failed:
        first = rows[failed[0]]
        log(f"fit study: {len(failed)} of {len(study.parts)} parts failed (part {failed[0]}: "
            f"{first['message']}); see {os.path.join(out, 'parts.csv')}; not merged (the same "
            "command reruns only the failed parts)")
        return summary
    merged = os.path.join(out, "fit")
    r = subprocess.run([binary(), *study.fit_arguments(), "--out", merged, "--merge",
                        *[folder.part_path(p) for p in study.parts]],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise StudyError(f"the merge of the parts failed: {r.stderr.strip()}")
    summary["merged"] = True
    log(f"fit study: {len(study.parts)} parts ({len(todo)} run in {elapsed:.1f} s) merged -> "
        f"{os.path.join(merged, 'fit.json')}, trials.csv, model.json, report.html")
    for line in r.stdout.splitlines():
        if line.startswith("mean e_q"):
            log(line)
    return summary


def read_study(path, chunk_size=None):
    """The study file at `path`: a FitStudy when it has "fit", else a run Study."""
    from .spec import Study
    path = os.fspath(path)
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        doc = json.loads(text)
    except (OSError, ValueError):
        return Study(path, chunk_size=chunk_size)  # which names the problem
    if isinstance(doc, dict) and "fit" in doc:
        if chunk_size is not None:
            raise StudyError(f"{path}: --chunk-size: a fit study runs one part a task (the fit "
                             "on all trials and one per fold)")
        return FitStudy(path, doc, text)
    return Study(path, chunk_size=chunk_size)
