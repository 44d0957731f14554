"""A rig dataset built from NumPy columns: a ball pressed into a plate and released, its normal
force made by a known stiffness plus noise; the fit recovers the stiffness.
"""
import numpy as np

import vcontact

kv_true = 3.0e12  # N/m^3
rng = np.random.default_rng(7)
t = np.linspace(0.0, 1.0, 400)
depth = 20e-6 * np.sin(np.pi * t) ** 2  # m, 0 -> 20 um -> 0
z = 0.01 - depth
vz = -20e-6 * np.pi * np.sin(2 * np.pi * t)  # dz/dt
ball, plate = vcontact.sphere(0.01), vcontact.halfspace()
fz = np.array([kv_true * vcontact.contact(ball, (0.0, 0.0, zi), plate, None)["aggregate"]["volume"]
               for zi in z])
fz += rng.normal(0.0, 0.01, size=t.size)  # 10 mN load-cell noise

zeros, ones = np.zeros_like(t), np.ones_like(t)
columns = {"t": t, "x": zeros, "y": zeros, "z": z, "qw": ones, "qx": zeros, "qy": zeros,
           "qz": zeros, "vx": zeros, "vy": zeros, "vz": vz, "wx": zeros, "wy": zeros,
           "wz": zeros, "fz": fz}
dataset = vcontact.Dataset.from_columns(
    columns, payload={"shape": "sphere", "radius": 0.01}, plate={"shape": "halfspace"},
    outputs=["fz"], noise={"fz": 0.01}, name="press")
fit = vcontact.fit(dataset, {"format": "vcontact.model/1", "effects": {"stiffness": {}}})
kv = next(p for p in fit["parameters"] if p["name"] == "stiffness.kv")
print(f"fitted kv = {kv['value']:.4e} +- {kv['std_error']:.1e} N/m^3 (true {kv_true:.4e})")
print(f"chi = {fit['comparison']['chi']:.3f}")
assert abs(kv["value"] / kv_true - 1) < 1e-3
