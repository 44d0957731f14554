"""Running a study: the output folder, the chunks on Dask (or in this process), progress, and
the merge into results.csv / results.h5 (docs/STUDY.md, "Running").

    DIR/manifest.json         the study's identity (study file, base scenario, design, chunk size)
    DIR/study.json            the study file as it was read
    DIR/chunks/chunk_NNNNNN.json   one per finished chunk, written atomically
    DIR/results.csv, results.h5, report.html   merged from the chunks, rewritten at the end

A rerun of the same command finds the chunk files, keeps them and runs the others; a folder
made by another study (any change of the study file, its base scenario or the design) is
refused, never mixed.
"""

import csv
import itertools
import json
import os
import sys
import threading
import time

import numpy as np

from .chunks import run_chunk
from .spec import StudyError

MANIFEST_FORMAT = "vcontact.study-run/1"
H5_AUTO_RUNS = 10_000  # results.h5 is written without --h5 from this many runs on
CONNECT_TIMEOUT_S = 5.0
# Set by the command's SIGINT/SIGTERM handler (__main__.py): an interrupt that arrives while
# Dask starts its cluster is caught inside Dask; the flag makes it count all the same.
INTERRUPT = threading.Event()


def _write_atomic(path, text):
    """Writes text to path through a temporary file in the same folder and a rename, so that a
    reader (or a resumed run) sees the whole file or none of it."""
    tmp = f"{path}.tmp.{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def open_folder(out, sub, study, manifest, changed):
    """Creates the output folder `out` with its folder `sub` of finished pieces, or checks that
    it holds this study (its manifest's identity); the first time writes the study file as read
    and the manifest. changed(old manifest) says, for the refusal, what study it holds and
    what changed."""
    path = os.path.join(out, "manifest.json")
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            old = json.load(f)
        if old.get("identity") != study.identity:
            raise StudyError(
                f"{out}: holds the results of another study ({changed(old)} since it was "
                "started; refusing to mix them: choose another --out, or remove the folder to "
                "start again")
    os.makedirs(sub, exist_ok=True)
    if not os.path.exists(path):
        _write_atomic(os.path.join(out, "study.json"), study.text)
        _write_atomic(path, json.dumps(manifest, indent=2) + "\n")


class Folder:
    """The output folder of one study."""

    def __init__(self, out, study):
        self.out = os.fspath(out)
        self.study = study
        self.chunk_dir = os.path.join(self.out, "chunks")

    def chunk_path(self, c):
        return os.path.join(self.chunk_dir, f"chunk_{c:06d}.json")

    def open(self):
        """Creates the folder, or checks that it holds this study; returns the finished chunks."""
        manifest = {"format": MANIFEST_FORMAT, "identity": self.study.identity,
                    "study": os.path.abspath(self.study.path), "runs": self.study.runs,
                    "chunk_size": self.study.chunk_size, "chunks": self.study.chunks,
                    "seed": self.study.seed}

        def changed(old):
            why = ("the chunk size differs" if old.get("chunk_size") != self.study.chunk_size
                   else "the study file, its base scenario or the sampled design changed")
            return f"{old.get('study')}, {old.get('runs')} runs): {why}"

        open_folder(self.out, self.chunk_dir, self.study, manifest, changed)
        return {c for c in range(self.study.chunks) if self._finished(c)}

    def _finished(self, c):
        p = self.chunk_path(c)
        if not os.path.exists(p):
            return False
        try:
            with open(p, encoding="utf-8") as f:
                return json.load(f).get("identity") == self.study.identity
        except (OSError, ValueError):
            return False  # unreadable: run it again

    def write_chunk(self, result):
        _write_atomic(self.chunk_path(result["chunk"]), json.dumps(result))

    def rows(self):
        """The runs in order, chunk by chunk (one chunk in memory at a time)."""
        for c in range(self.study.chunks):
            with open(self.chunk_path(c), encoding="utf-8") as f:
                yield from json.load(f)["rows"]


class Progress:
    """One line on standard error, rewritten, only for a person watching (a terminal, CI unset),
    as every vcontact command does (io/progress.hpp)."""

    INTERVAL_S = 0.5

    def __init__(self, total_runs, quiet, unit="runs"):
        self.total = total_runs
        self.unit = unit
        self.shown = not quiet and sys.stderr.isatty() and not os.environ.get("CI")
        self.start = self.last = time.monotonic()
        self.width = 0

    def update(self, done, failed, force=False):
        now = time.monotonic()
        if not self.shown or (not force and now - self.last < self.INTERVAL_S):
            return
        self.last = now
        elapsed = now - self.start
        line = f"study: {done}/{self.total} {self.unit} ({100.0 * done / self.total:.0f} %)"
        if failed:
            line += f", {failed} failed"
        line += f", {elapsed:.0f} s"
        sys.stderr.write("\r" + line.ljust(self.width))
        sys.stderr.flush()
        self.width = len(line)

    def finish(self):
        if self.shown and self.width:
            sys.stderr.write("\n")
            sys.stderr.flush()


def _chunk_args(study, c):
    first = c * study.chunk_size
    last = min(study.runs, first + study.chunk_size)
    return c, first, study.rows[first:last].tolist()


def _failures(result):
    return sum(r["status"] != "completed" for r in result["rows"])


def _run_here(study, folder, todo, progress, done, failed, threads):
    spec = study.task_spec()
    for c in todo:
        result = run_chunk(spec, *_chunk_args(study, c), threads=threads)
        folder.write_chunk(result)
        done += len(result["rows"])
        failed += _failures(result)
        progress.update(done, failed)
    return done, failed


def _package_dir():
    """The folder holding the package vcontact (build/python in a build tree)."""
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def connect(scheduler, workers):
    """A Dask client: to a running scheduler (its address), or to a LocalCluster of `workers`
    processes of one thread each. The local workers import vcontact from where this process
    did (PYTHONPATH)."""
    from distributed import Client, LocalCluster
    if scheduler:
        try:
            return Client(scheduler, timeout=CONNECT_TIMEOUT_S), None
        except (OSError, TimeoutError) as e:
            raise StudyError(f"--scheduler {scheduler}: no Dask scheduler answered within "
                             f"{CONNECT_TIMEOUT_S:g} s ({type(e).__name__}: {e})") from None
    import dask
    # Dask's statistical profiler samples every worker thread each 10 ms: 1.5 % of a core per
    # idle worker measured here (3.6 % with it, 2.1 % without; docs/STUDY.md, "Measurements");
    # a study has no use for it. The local workers inherit the setting.
    dask.config.set({"distributed.worker.profile.enabled": False})
    paths = [_package_dir()] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    os.environ["PYTHONPATH"] = os.pathsep.join(dict.fromkeys(paths))
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=40)
    return Client(cluster), cluster


def _run_dask(study, folder, todo, progress, done, failed, client):
    """Chunks as Dask tasks, a window of them in flight (a few per worker thread, so that the
    scheduler and the client hold little whatever the study's size); each finished chunk is
    written as it comes. Tasks are pure and named by the study's identity and chunk index, so a
    chunk whose worker died is run again elsewhere by the scheduler, with the same result."""
    from distributed import as_completed
    spec = client.scatter(study.task_spec(), broadcast=True, hash=False)
    threads = max(1, sum(client.nthreads().values()))
    window = 4 * threads
    pending = iter(todo)

    def submit(c):
        return client.submit(run_chunk, spec, *_chunk_args(study, c), threads=1,
                             key=f"vcontact-chunk-{study.identity[:16]}-{c}", pure=True)

    running = as_completed([submit(c) for c in itertools.islice(pending, window)])
    for future in running:
        try:
            result = future.result()
        except Exception as e:  # the task itself failed: not a run (runs fail as rows)
            raise StudyError(
                f"chunk {future.key.rpartition('-')[2]} failed on the cluster: "
                f"{type(e).__name__}: {e} (do its workers import this vcontact? start them "
                f"with PYTHONPATH={_package_dir()})") from None
        future.release()
        folder.write_chunk(result)
        done += len(result["rows"])
        failed += _failures(result)
        progress.update(done, failed)
        nxt = next(pending, None)
        if nxt is not None:
            running.add(submit(nxt))
    return done, failed


def run_study(study, out, workers=None, scheduler=None, quiet=False, h5=False,
              threads=0, log=None, client=None):
    """Runs (or resumes) the study into `out`, then merges the table and writes the report.
    workers 0: no Dask, the chunks one after another in this process on `threads` TBB threads;
    `client`: a Dask client of the caller's (kept open).
    Returns the merged table's summary {runs, completed, stopped, error, resumed_chunks}."""
    log = log or (lambda text: print(f"vcontact: {text}", file=sys.stderr))
    folder = Folder(out, study)
    finished = folder.open()
    todo = [c for c in range(study.chunks) if c not in finished]
    done = sum(min(study.chunk_size, study.runs - c * study.chunk_size) for c in finished)
    if finished:
        log(f"resuming {out}: {len(finished)} of {study.chunks} chunks already finished, "
            f"{len(todo)} to run")
    progress = Progress(study.runs, quiet)
    own, cluster = client is None, None
    start = time.monotonic()
    try:
        if todo and client is not None:
            _run_dask(study, folder, todo, progress, done, 0, client)
        elif todo and workers == 0 and not scheduler:
            _run_here(study, folder, todo, progress, done, 0, threads)
        elif todo:
            client, cluster = connect(scheduler, workers or os.cpu_count() or 1)
            if INTERRUPT.is_set():  # came while Dask started, which swallows KeyboardInterrupt
                raise KeyboardInterrupt
            _run_dask(study, folder, todo, progress, done, 0, client)
    finally:
        progress.finish()
        if own and client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    elapsed = time.monotonic() - start
    table = merge(study, folder, h5=h5 or study.runs >= H5_AUTO_RUNS)
    from .report import write_report
    write_report(study, table, os.path.join(out, "report.html"), out)
    counts = {s: int(np.sum(table["status"] == s)) for s in ("completed", "stopped", "error")}
    log(f"study: {study.runs} runs ({counts['completed']} completed, {counts['stopped']} stopped, "
        f"{counts['error']} errors; {len(todo)} chunks run in {elapsed:.1f} s) -> "
        f"{os.path.join(out, 'results.csv')}, report.html")
    return {"runs": study.runs, **counts, "resumed_chunks": len(finished),
            "chunks_run": len(todo)}


def columns(study):
    return (["run", "seed"] + study.names + [o["name"] for o in study.outputs]
            + ["status", "message", "wall_time_s"])


def _number(v):
    return repr(float(v))  # the shortest text that reads back to the same double


def merge(study, folder, h5=False):
    """results.csv (and results.h5) from the chunk files, runs in order, written atomically.
    Returns the table as NumPy columns (for the report)."""
    names = columns(study)
    n_out = len(study.outputs)
    table = {"run": np.arange(study.runs), "seed": np.full(study.runs, study.seed)}
    for j, name in enumerate(study.names):
        table[name] = study.rows[:, j]
    outputs = np.empty((study.runs, n_out))
    status = np.empty(study.runs, dtype=object)
    message = np.empty(study.runs, dtype=object)
    wall = np.empty(study.runs)
    tmp = os.path.join(folder.out, f"results.csv.tmp.{os.getpid()}")
    with open(tmp, "w", encoding="utf-8", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(names)
        for row in folder.rows():
            i = row["run"]
            outputs[i] = row["outputs"]
            status[i], message[i], wall[i] = row["status"], row["message"], row["wall_time"]
            w.writerow([i, study.seed] + [_number(v) for v in study.rows[i]]
                       + [_number(v) for v in row["outputs"]]
                       + [row["status"], row["message"], _number(row["wall_time"])])
    os.replace(tmp, os.path.join(folder.out, "results.csv"))
    for j, o in enumerate(study.outputs):
        table[o["name"]] = outputs[:, j]
    table.update({"status": status, "message": message, "wall_time_s": wall})
    if h5:
        _write_h5(table, names, os.path.join(folder.out, "results.h5"), study)
    return table


def _write_h5(table, names, path, study):
    """results.h5: one dataset per column (strings as UTF-8), the study's identity, seed and
    source as attributes."""
    import h5py
    tmp = f"{path}.tmp.{os.getpid()}"
    with h5py.File(tmp, "w") as f:
        for name in names:
            data = table[name]
            if data.dtype == object:
                f.create_dataset(name, data=data.astype(str).tolist(),
                                 dtype=h5py.string_dtype("utf-8"), compression="gzip")
            else:
                f.create_dataset(name, data=data, compression="gzip")
        f.attrs["identity"] = study.identity
        f.attrs["seed"] = study.seed
        f.attrs["study"] = study.text
    os.replace(tmp, path)
