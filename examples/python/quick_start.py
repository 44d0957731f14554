"""The README's ten-line example (run from the repository's folder, or anywhere: it finds it)."""
import os
os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
# --- as in the README -----------------------------------------------------------------------
import vcontact
ball, plate = vcontact.sphere(0.01), vcontact.halfspace()
c = vcontact.contact(ball, vcontact.pose(p=(0, 0, 0.0095)), plate, None)   # 0.5 mm deep
print(c["aggregate"]["volume"], c["aggregate"]["centroid"], len(c["patches"]))
model = vcontact.Model.from_file("assets/scenarios/steel_on_aluminium.model.json")
print(model.wrench(c["aggregate"], v_c=(0.01, 0, 0))["force"])              # sliding at 1 cm/s
run = vcontact.Scenario.load("assets/scenarios/ball_drop.json").run(out="out/ball_drop")
z = run["bodies"]["ball"]["p"][:, 2]                                          # NumPy, one per output
print(z.min(), run["pairs"]["ball-plate"]["f_n"].max())
vcontact.view("out/ball_drop", "out/ball_drop/view.html")                     # docs/VIEWER.md
