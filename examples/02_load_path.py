"""Thrust on the right support along a load path, for three settlements (the paper, Fig. 8).

The arch is loaded by lambda times its self-weight along +x; the right support settles
inward, outward or downward by 1 mm. Below the limit the thrusts differ; at lambda_0max
(0.243) every scenario reaches the same limit state. Run: ``python examples/02_load_path.py``.
"""

from tce import Analysis, Material, load_path, semicircular_arch

MM = 1e-3
SCENARIOS = {
    "inward": [-MM, 0, 0, 0, 0, 0],
    "outward": [MM, 0, 0, 0, 0, 0],
    "downward": [0, 0, -MM, 0, 0, 0],
}

arch = semicircular_arch()
an = Analysis(arch, Material())  # Heyman: no tension, no friction limit
W = arch.total_weight
right = arch.support_names.index("right")
paths = {name: load_path(an, 0.0, {"right": u}, step=0.05, atol=1e-6) for name, u in SCENARIOS.items()}

print(f"total weight W = {W:.4f} kN; thrust H and vertical reaction V of the right support, / W")
print("lambda  " + "  ".join(f"{name:>17s}" for name in SCENARIOS))
for k in range(0, 5):
    lam = 0.05 * k
    row = []
    for lp in paths.values():
        r = next(s for s in lp.path if abs(s.lam - lam) < 1e-12)
        H, V = r.support_wrenches[right, [0, 2]] / W
        row.append(f"H {H:+.4f} V {V:.4f}")
    print(f"{lam:6.3f}  " + "  ".join(row))
for name, lp in paths.items():
    H, V = lp.at_limit.support_wrenches[right, [0, 2]] / W
    print(f"{name:>8s}: lambda_max {lp.lambda_max:.7f} (direct {lp.lambda_direct:.7f}), at the limit H {H:+.4f} V {V:.4f}")
