#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz harnesses from assets/ (tests/fuzz/README.md).

Usage: make_seeds.py ASSETS_DIR OUT_DIR   (OUT_DIR/<harness>/ gets one file a seed)
"""

import glob
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bad_inputs"))

import cases_mesh  # noqa: E402

# Larger meshes slow every fuzzing run; a seed shows the format, not the size.
MAX_MESH_SEED_BYTES = 200_000
EXTENSION_BYTE = {".stl": 0, ".obj": 1, ".off": 2, ".ply": 3}


def write(folder, name, data):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def mesh_seeds(assets, out):
    folder = os.path.join(out, "mesh_reader")
    for path in glob.glob(assets + "/**/*.stl", recursive=True):
        if os.path.getsize(path) <= MAX_MESH_SEED_BYTES:
            with open(path, "rb") as f:
                write(folder, os.path.basename(path), bytes([0]) + f.read())
    cube = cases_mesh.cube_triangles()
    generated = {"cube_ascii.stl": cases_mesh.stl_ascii(cube).encode(),
                 "cube_binary.stl": cases_mesh.stl_binary(cube),
                 "cube.obj": cases_mesh.obj(cube).encode(),
                 "cube.off": cases_mesh.off().encode(),
                 "cube.ply": cases_mesh.ply().encode()}
    for name, data in generated.items():
        write(folder, name, bytes([EXTENSION_BYTE[os.path.splitext(name)[1]]]) + data)


def json_seeds(assets, out):
    for path in glob.glob(assets + "/scenarios/*.json"):
        harness = "model" if path.endswith(".model.json") else "scenario"
        with open(path, "rb") as f:
            write(os.path.join(out, harness), os.path.basename(path), f.read())
    for path in glob.glob(assets + "/datasets/models/*.json"):
        with open(path, "rb") as f:
            write(os.path.join(out, "model"), os.path.basename(path), f.read())


def dataset_seeds(assets, out):
    for path in glob.glob(assets + "/datasets/*.json"):
        with open(path) as f:
            sidecar = json.load(f)
        with open(os.path.join(os.path.dirname(path), sidecar["data"])) as f:
            csv = "".join(f.readlines()[:40])
        sidecar["data"] = "rig.csv"
        write(os.path.join(out, "dataset"), os.path.basename(path),
              json.dumps(sidecar).encode() + b"\0" + csv.encode())


def shape_pose_seeds(out):
    texts = ["sphere:0.01", "cylinder:0.01,0.02", "box:0.1,0.2,0.3", "halfspace",
             "0,0,0.015", "0,0,0,10,20,30", "0,0,0,1,0,0,0", "part.stl@mm", "a@b/c.obj@0.001",
             "1e-3,-2.5E+2,+0.5"]
    for i, t in enumerate(texts):
        write(os.path.join(out, "shape_pose"), "seed%d" % i, t)


# Formulas of docs/EXTENDING.md and of the grammar's edges; NULs separate the normal,
# tangential and spin terms (expression_fuzz.cpp).
FORMULAS = ["\0-b*f_n^2", "\0-c2*f_n*max(v_t, v_eps)",
            "\0\0-c2*r_gyr^2*f_n*max(abs(omega_n), v_eps/r_gyr)",
            "kv*V*(1 + b*ddot)\0-mu_max*f_n*(s_mu < 0.5 ? 1 : s)",
            "\0-b*t*f_n + sum(1, 2, 3)*avg(C_v, C_w)/_pi",
            "sqrt(max(V, 0))*atan2(omega_t, 1)\0-(f_n >= 1 && v_avg != 0 || mu_C == 0)",
            "\0-0,001*f_n", "\0-max(0,001*f_n, b)", "\00*(f_n=1e3)+f_n", "\0-b*f_n^",
            "\0" + "b+" * 2600 + "b"]


def expression_seeds(out):
    for i, f in enumerate(FORMULAS):
        write(os.path.join(out, "expression"), "seed%d" % i, f)


def candidates_seeds(out):
    mu_load = {"kind": "expression",
               "parameters": {"b": {"value": 0, "unit": "1/N", "lower": 0, "upper": 1}},
               "tangential": "-b*f_n^2", "requires": ["stiffness", "coulomb"]}
    files = {"library": {"viscous": {}, "stribeck": {"mu_s": 0.3}, "bristle": {}},
             "expression": {"mu_load": mu_load},
             "both": {"viscous": {}, "mu_load": mu_load}}
    for name, candidates in files.items():
        write(os.path.join(out, "candidates"), name + ".json",
              json.dumps({"format": "vcontact.candidates/1", "candidates": candidates}))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    assets, out = sys.argv[1], sys.argv[2]
    mesh_seeds(assets, out)
    json_seeds(assets, out)
    dataset_seeds(assets, out)
    shape_pose_seeds(out)
    expression_seeds(out)
    candidates_seeds(out)


if __name__ == "__main__":
    main()
