"""One contact query: a CAD ball mesh and the exact sphere pressed 0.5 mm into a plate.

Prints the aggregate and each patch with every ContactVolume field, and the faceting error of
the mesh (README, "What the demo shows").
"""
import os

import numpy as np

import vcontact

ASSETS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "assets")

ball_mesh = vcontact.load_mesh(os.path.join(ASSETS, "meshes", "ball_r10mm.stl"))
ball = vcontact.sphere(0.01)
plate = vcontact.halfspace()
X_WA = vcontact.pose(p=(0.0, 0.0, 0.0095))  # 4x4; (p, quaternion) or "x,y,z" work as well

exact = vcontact.contact(ball, X_WA, plate, np.eye(4))
faceted = vcontact.contact(ball_mesh, X_WA, plate, np.eye(4))
for label, c in (("sphere (analytic)", exact), ("mesh (halfspace clip)", faceted)):
    print(f"{label}: {len(c['patches'])} patch(es)")
    for key, value in c["aggregate"].items():
        print(f"  {key:15s} {value}")
ratio = faceted["aggregate"]["volume"] / exact["aggregate"]["volume"] - 1
print(f"mesh volume against the exact sphere: {100 * ratio:+.2f} %")
assert exact["in_contact"] and faceted["in_contact"]
