"""The paper's semicircular arch under a settlement, a lateral load and out-of-plane rocking.

The README's "Use it from Python" example. Run: ``python examples/01_arch_settlement.py``.
"""

from tce import Analysis, Material, load_path, semicircular_arch

arch = semicircular_arch(inner_radius=1.0, thickness=0.2, depth=0.25, voussoirs=14)  # m
an = Analysis(arch, Material(friction=0.8))            # model chosen per scene: planar LP or 3D SOCP
r = an.solve(lam=0.1, alpha=0.0, settlements={"right": [0.001, 0, 0, 0, 0, 0]})  # m, rad
print(r.status, r.model)                               # optimal planar
print(r.support_wrenches)                              # (Fx, Fy, Fz, Mx, My, Mz) per support, kN and kN m
print(an.limit(90.0).lambda_max)                       # 0.17876: out-of-plane rocking
lp = load_path(an, alpha=0.0, settlements={"right": [0, 0, -0.001, 0, 0, 0]}, step=0.02, atol=1e-6)
print(lp.lambda_max, lp.lambda_direct, lp.gap)         # 0.242824: bisection vs direct limit
