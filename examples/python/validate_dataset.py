"""The validation workflow on a bundled rig dataset: compare a model, fit it, diagnose it.

Each call returns the content of the JSON file its command writes (compare.json, fit.json,
diagnosis.json), as dicts.
"""
import os

import vcontact

ASSETS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "assets")
dataset = vcontact.Dataset.load(os.path.join(ASSETS, "datasets", "drive.json"))
bare = os.path.join(ASSETS, "datasets", "models", "bare.model.json")
print(f"{dataset.name}: {dataset.size} samples, outputs {dataset.outputs}")

c = vcontact.compare(dataset, bare)
print(f"bare model as given: chi = {c['chi']:.2f}")
f = vcontact.fit(dataset, bare)
print(f"bare model fitted: chi = {f['comparison']['chi']:.2f}, model {f['model']['effects']}")
d = vcontact.diagnose(dataset, bare, iterate=True)
print("diagnosis: verdict", d["verdict"], "final model", d["model"]["effects"])
