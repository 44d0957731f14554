"""python3 -m vcontact.study: the implementation of `vcontact study` (docs/STUDY.md).

Exit status: 0 done (failed runs are rows of the table, not an error of the study), 2 bad input
(the study file, its scenario, an option, an output folder of another study, an unreachable
scheduler), 1 a fit study whose parts did not all finish (parts.csv says why; not merged), 130 interrupted (finished chunks are kept; the same command resumes)."""

import argparse
import signal
import sys

BAD_INPUT = 2
PARTS_FAILED = 1  # a fit study with parts that failed: not merged, the rerun resumes
INTERRUPTED = 130


def _parser():
    p = argparse.ArgumentParser(
        prog="vcontact study",
        description="Run a study (vcontact.study/1, docs/STUDY.md): many runs of a scenario "
                    "with parameters varied, in chunks on Dask; results.csv, report.html. A "
                    "study with \"fit\": the parts of a cross-validated trajectory fit on "
                    "Dask, merged into fit/.")
    p.add_argument("study", metavar="STUDY", help="study JSON file")
    p.add_argument("--out", required=True, help="output folder (rerun to resume)")
    p.add_argument("--workers", type=int, default=None,
                   help="local Dask worker processes (default: one per core); 0: no Dask, "
                        "the chunks in this process")
    p.add_argument("--scheduler", default=None, help="address of a running Dask scheduler, "
                   "tcp://HOST:PORT (its workers must see the study's files at the same paths)")
    p.add_argument("--chunk-size", type=int, default=None,
                   help="runs per Dask task (default: the study's chunk_size, else ~1/100 of "
                        "the runs, at most 1000)")
    p.add_argument("--threads", type=int, default=0,
                   help="with --workers 0: TBB threads for the runs (default 0: every core)")
    p.add_argument("--run", type=int, default=None,
                   help="run only this run, alone, with the output of `vcontact simulate` in "
                        "--out (to reproduce it)")
    p.add_argument("--h5", action="store_true", help="also write results.h5 (always from "
                   "10000 runs on)")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    return p


def _stop(signum, frame):
    from .runner import INTERRUPT
    INTERRUPT.set()
    raise KeyboardInterrupt


def main(argv=None):
    args = _parser().parse_args(argv)
    from . import StudyError, run_one, run_study
    from .fit import read_study, run_fit_study
    from .expr import ExpressionError
    # A batch system's kill ends as an interrupt does; both are remembered (runner.INTERRUPT).
    signal.signal(signal.SIGTERM, _stop)
    signal.signal(signal.SIGINT, _stop)
    try:
        if args.workers is not None and args.workers < 0:
            raise StudyError("--workers: expected 0 (no Dask) or a number of processes")
        if args.scheduler and args.workers is not None:
            raise StudyError("--scheduler and --workers exclude each other: the cluster's "
                             "workers are its own")
        study = read_study(args.study, chunk_size=args.chunk_size)
        if study.kind == "fit":
            for given, option in ((args.run is not None, "--run"), (args.h5, "--h5"),
                                  (args.threads, "--threads")):
                if given:
                    raise StudyError(f"{option}: not an option of a fit study (each part is "
                                     "`vcontact fit --fold`; docs/STUDY.md, \"Fit studies\")")
            summary = run_fit_study(study, args.out, workers=args.workers,
                                    scheduler=args.scheduler, quiet=args.quiet)
            return 0 if summary["merged"] else PARTS_FAILED
        if args.run is not None:
            result = run_one(study, args.run, args.out)
            status = result["summary"]["status"]
            print(f"vcontact: run {args.run} of {args.study}: {status}; output in {args.out}",
                  file=sys.stderr)
            return 0
        run_study(study, args.out, workers=args.workers, scheduler=args.scheduler,
                  quiet=args.quiet, h5=args.h5, threads=args.threads)
    except (StudyError, ExpressionError, ValueError) as e:
        print(f"vcontact: error: {e}", file=sys.stderr)
        return BAD_INPUT
    except KeyboardInterrupt:
        print(f"vcontact: interrupted: the finished chunks (parts, of a fit study) are kept in "
              f"{args.out}; the same "
              "command resumes", file=sys.stderr)
        return INTERRUPTED
    return 0


if __name__ == "__main__":
    sys.exit(main())
