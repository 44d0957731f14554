"""vcontact: volumetric contact between rigid bodies, from Python.

Shapes, poses and contact queries; force models; scenarios; rig datasets with compare, fit and
diagnose. Every length is in metres. docs/PYTHON.md describes each function; errors of the
engine arrive as vcontact.InputError (a ValueError) carrying the engine's message.
"""

import json
import os
import tempfile

import numpy as np

from . import _vcontact
from ._vcontact import Dataset, InputError, Model, Scenario, Shape

__all__ = [
    "InputError", "SimulationError", "Shape", "Model", "Scenario", "Dataset",
    "sphere", "cylinder", "box", "halfspace", "shape", "load_mesh", "mesh", "pose",
    "contact", "compare", "fit", "diagnose", "view",
]


class SimulationError(RuntimeError):
    """A run that stopped (NaN, step-size collapse, penetration beyond its bound).

    `result` holds the series up to the stop, as Scenario.run returns them.
    """

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


def _plain(value):
    """json.dumps fallback: NumPy arrays and scalars as lists and numbers."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"{type(value).__name__} is not JSON serialisable")


# --- shapes and poses -------------------------------------------------------------------------

def sphere(radius):
    """Sphere of `radius`, centred on its frame's origin."""
    return _vcontact.shape(f"sphere:{float(radius)!r}")


def cylinder(radius, length):
    """Cylinder of `radius` and `length` along its frame's z axis, centred."""
    return _vcontact.shape(f"cylinder:{float(radius)!r},{float(length)!r}")


def box(x, y, z):
    """Box with these edge lengths, centred, edges along its frame's axes."""
    return _vcontact.shape(f"box:{float(x)!r},{float(y)!r},{float(z)!r}")


def halfspace():
    """The solid z <= 0 of its frame."""
    return _vcontact.shape("halfspace")


def shape(text, repair=False, fill_holes=False):
    """A shape from the command line's text: 'sphere:0.01', 'part.stl@mm', ..."""
    return _vcontact.shape(text, repair, fill_holes)


def load_mesh(path, scale=1.0, repair=False, fill_holes=False):
    """A closed triangle mesh from a file; `scale` (a number or 'mm', 'in', ...) into metres."""
    scale_text = scale if isinstance(scale, str) else repr(float(scale))
    return _vcontact.shape(f"{os.fspath(path)}@{scale_text}", repair, fill_holes)


def mesh(vertices, faces, name="mesh", repair=False, fill_holes=False):
    """A closed mesh from an (n, 3) vertex array (metres) and an (m, 3) face array.

    The mesh is checked (and optionally repaired) as a mesh file is.
    """
    return _vcontact.mesh_from_arrays(vertices, faces, name, repair, fill_holes)


def pose(p=(0.0, 0.0, 0.0), q=(1.0, 0.0, 0.0, 0.0)):
    """The 4x4 matrix of translation `p` and unit quaternion `q` = (w, x, y, z)."""
    return _vcontact.pose_matrix((np.asarray(p, float), np.asarray(q, float)))


def contact(a, X_WA, b, X_WB, method=None, depth=False):
    """The interference of shape `a` at pose X_WA with shape `b` at X_WB.

    Poses are 4x4 arrays, (p, quaternion wxyz) pairs, 3-vectors or pose text. Returns
    {"in_contact", "aggregate", "patches"}; the aggregate and every patch carry every
    ContactVolume field (volume, centroid, normal, depth, area, r_gyr, J_v, J_s,
    relative_error, method, in_contact).

    depth=True computes the exact deepest column of the `fast` method (the default for two
    meshes), a pass that makes its query 3-4x as long; without it a `fast` region's
    "depth" is None. Every other method fills "depth" either way, and every other field is
    the same either way.
    """
    return _vcontact.contact(a, X_WA, b, X_WB, method, depth)


# --- models -------------------------------------------------------------------------------------

def _model_from_dict(d, source="dict"):
    """A model from a dict in the model-file format (docs/DATASET.md, "Model files")."""
    return Model.from_json(json.dumps(d, default=_plain), source)


def _model_to_dict(self):
    """The model as the dict its model file holds."""
    return json.loads(self.to_json())


def _model_parameters(self):
    """{qualified name: value}."""
    return {n: self.parameter(n) for n in self.parameter_names}


Model.from_dict = staticmethod(_model_from_dict)
Model.to_dict = _model_to_dict
Model.parameters = property(_model_parameters)


# --- scenarios ----------------------------------------------------------------------------------

_run = Scenario.run


def _scenario_run(self, out=None, check=True):
    """Runs the scenario; returns {"bodies": {name: series}, "pairs": {name: series}, "summary"}.

    Body series: t (n,), p (n, 3), q (n, 4) wxyz, v (n, 3), w (n, 3). Pair series: t, V, depth,
    area, r_gyr, centroid, normal, force, torque (on body A about the centroid), f_n, s,
    mu_max. With `out`, the CSVs and summary.json of `vcontact simulate` are written there too.
    A stopped run raises SimulationError (its `result` keeps the series) unless check=False.
    """
    result = _run(self, None if out is None else os.fspath(out))
    status = result["summary"]["status"]
    if check and status != "completed":
        raise SimulationError(f"{self.path}: simulation stopped: {status}", result)
    return result


Scenario.run = _scenario_run


def view(out_dir, html, scenario="", dataset=""):
    """Writes the 3D playback page of a simulation output folder, or of the folder `vcontact
    compare` wrote for a dynamic dataset (the record as a ghost; docs/VIEWER.md)."""
    return _vcontact.view(os.fspath(out_dir), os.fspath(html), os.fspath(scenario),
                          os.fspath(dataset))


# --- datasets -----------------------------------------------------------------------------------

def _dataset_from_columns(columns, payload, plate, outputs, noise=None, name="dataset",
                          notes=""):
    """A dataset from NumPy columns (names as in docs/DATASET.md: t, x, y, z, qw, qx, qy, qz,
    vx..., fx...), and payload and plate shapes as sidecar objects ({"shape": "sphere",
    "radius": 0.01}). The columns go through the same checks as a file's."""
    names = list(columns)
    table = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    with tempfile.TemporaryDirectory(prefix="vcontact-dataset-") as tmp:
        csv = os.path.join(tmp, "data.csv")
        np.savetxt(csv, table, delimiter=",", header=",".join(names), comments="", fmt="%.17g")
        sidecar = {"format": "vcontact.dataset/1", "mode": "kinematic", "data": "data.csv",
                   "name": name, "notes": notes, "payload": payload, "plate": plate,
                   "outputs": list(outputs)}
        if noise:
            sidecar["noise"] = noise
        path = os.path.join(tmp, name + ".json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(sidecar, f, default=_plain)
        try:
            return Dataset.load(path)
        except InputError as e:  # name the columns, not the temporary files
            message = str(e).replace(path, f"dataset '{name}'").replace(csv, "its columns")
            raise InputError(message) from None


Dataset.from_columns = staticmethod(_dataset_from_columns)


def _model(model):
    if isinstance(model, Model):
        return model
    if isinstance(model, dict):
        return Model.from_dict(model)
    return Model.from_file(os.fspath(model))


def _dataset(dataset):
    return dataset if isinstance(dataset, Dataset) else Dataset.load(os.fspath(dataset))


def compare(dataset, model):
    """compare.json's content: chi, rms and sigma per output, samples, residuals."""
    return json.loads(_vcontact.compare_json(_dataset(dataset), _model(model)))


def fit(dataset, model, loss="none", max_iterations=100):
    """fit.json's content; its "model" is the fitted model file (as a dict)."""
    return json.loads(_vcontact.fit_json(_dataset(dataset), _model(model), loss, max_iterations))


def diagnose(dataset, model, iterate=False, loss="none", max_iterations=100):
    """diagnosis.json's content, plus "model": the final model file (as a dict)."""
    return json.loads(_vcontact.diagnose_json(_dataset(dataset), _model(model), iterate, loss,
                                              max_iterations))
