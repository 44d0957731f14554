#!/usr/bin/env python3
"""A catalogue of bad inputs for every vcontact command (issue 20).

Usage: catalogue.py VCONTACT_BINARY ASSETS_DIR [NAME_FILTER]

Each case writes its input files into a fresh folder, runs one command there and asserts
  - the exit code (2 for bad input unless the case says otherwise),
  - that standard error holds every expected fragment (the file or option, the place, the
    expectation), and no "internal error",
  - that none of the case's output paths exists afterwards,
  - that the command ends within the time limit (a hang is a failure).
A case marked `pending` names what it waits for; it runs and is reported, but its failure
does not fail the catalogue (when it passes, the report says so, so the mark can go).
The cases themselves are in cases_*.py beside this file.
"""

import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import cases_cli  # noqa: E402
import cases_data  # noqa: E402
import cases_mesh  # noqa: E402
import cases_scenario  # noqa: E402
import cases_shape  # noqa: E402

# A bad input is refused before any real work, in well under a second; 60 s allows a loaded
# machine, and anything longer is a hang (a PLY header that never ends hung the reader).
TIME_LIMIT_S = 60


def run_case(case, binary, assets):
    with tempfile.TemporaryDirectory(prefix="vcontact-bad-") as folder:
        for name, content in case.files(assets).items():
            path = os.path.join(folder, name)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            mode = "wb" if isinstance(content, bytes) else "w"
            with open(path, mode) as f:
                f.write(content)
        for name in case.folders:
            os.makedirs(os.path.join(folder, name), exist_ok=True)
        argv = [binary] + [a.format(assets=assets, dir=folder) for a in case.args]
        try:
            done = subprocess.run(argv, cwd=folder, capture_output=True, timeout=TIME_LIMIT_S,
                                  stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            return ["no answer within %d s (hang)" % TIME_LIMIT_S]
        err = done.stderr.decode("utf-8", "replace")
        problems = []
        if done.returncode != case.code:
            problems.append("exit %d, expected %d" % (done.returncode, case.code))
        if "internal error" in err:
            problems.append("an internal error instead of a message")
        for fragment in case.expect:
            if fragment.format(dir=folder) not in err:
                problems.append("message lacks %r" % fragment)
        for out in case.outputs:
            if os.path.lexists(os.path.join(folder, out)):
                problems.append("output %s exists" % out)
        if problems:
            problems.append("stderr: " + err.strip()[-400:])
        return problems


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    binary, assets = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    only = sys.argv[3] if len(sys.argv) > 3 else ""
    cases = (cases_shape.CASES + cases_mesh.CASES + cases_scenario.CASES + cases_data.CASES +
             cases_cli.CASES)
    names = [c.name for c in cases]
    duplicates = {n for n in names if names.count(n) > 1}
    if duplicates:
        sys.exit("catalogue: case names used twice: %s" % sorted(duplicates))
    failed, pending_failed, pending_passed, ran = [], [], [], 0
    for case in cases:
        if only not in case.name:
            continue
        ran += 1
        problems = run_case(case, binary, assets)
        if case.pending and problems:
            pending_failed.append(case.name)
            print("PENDING %s (%s)" % (case.name, case.pending))
        elif problems:
            failed.append(case.name)
            print("FAIL %s: %s" % (case.name, " ".join(case.args)))
            for p in problems:
                print("    " + p)
        elif case.pending:
            pending_passed.append(case.name)
            print("PASSES NOW %s (marked pending: %s)" % (case.name, case.pending))
    print("%d cases: %d as expected, %d failed, %d pending" %
          (ran, ran - len(failed) - len(pending_failed), len(failed), len(pending_failed)))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
