"""A force model from a dict, and its normal force against depth for a sphere on a plate.

The wrench is evaluated at each depth for a 1 mm/s approach (damping) and 5 mm/s sliding
(Coulomb friction), from the zero pair state.
"""
import vcontact

model = vcontact.Model.from_dict({
    "format": "vcontact.model/1",
    "effects": {"stiffness": {"kv": 5.17e12}, "damping": {"a": 0.3},
                "coulomb": {"mu": 0.2, "v_s": 1e-3}},
})
print("parameters:", model.parameters)
ball, plate = vcontact.sphere(0.01), vcontact.halfspace()
print(f"{'depth um':>9} {'V m^3':>11} {'f_n N':>9} {'f_x N':>9}")
for depth_um in (1, 2, 5, 10, 20, 50):
    c = vcontact.contact(ball, (0.0, 0.0, 0.01 - depth_um * 1e-6), plate, None)
    w = model.wrench(c["aggregate"], v_c=(0.005, 0.0, -0.001))
    print(f"{depth_um:9d} {c['aggregate']['volume']:11.3e} {w['f_n']:9.3f} {w['force'][0]:9.3f}")
    assert w["force"][0] < 0  # friction opposes the sliding
