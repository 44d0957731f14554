"""Runs the bundled ball drop, reads its series as NumPy arrays and writes the 3D viewer page.

Writes ball_drop_out/ (the CSVs of `vcontact simulate`) and ball_drop_view.html in the
current folder; open the page in a browser (docs/VIEWER.md).
"""
import os

import numpy as np

import vcontact

ASSETS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "assets")

scenario = vcontact.Scenario.load(os.path.join(ASSETS, "scenarios", "ball_drop.json"))
result = scenario.run(out="ball_drop_out")
ball = result["bodies"]["ball"]
pair = result["pairs"]["ball-plate"]
impacts = np.flatnonzero((pair["V"][1:] > 0) & (pair["V"][:-1] == 0))
print(f"{len(ball['t'])} outputs, real-time factor {result['summary']['real_time_factor']:.0f}")
print("first contacts at t =", np.round(pair["t"][impacts + 1][:5], 4), "s")
print(f"peak normal force {pair['f_n'].max():.1f} N, at rest {pair['f_n'][-1]:.3f} N")
print(f"rest height of the centre {ball['p'][-1, 2] * 1e3:.4f} mm")
for warning in vcontact.view("ball_drop_out", "ball_drop_view.html"):
    print("note:", warning)
print("wrote ball_drop_view.html")
