"""Direct limit analysis of the paper's arch: lambda_0max and its four-hinge mechanism.

lambda_max comes from one conic program; its dual gives the collapse mechanism, whose hinges
open alternately at the intrados and the extrados (Heyman). Run:
``python examples/05_limit_mechanism.py``.
"""

import numpy as np

from tce import Analysis, Material, semicircular_arch

arch = semicircular_arch()
lim = Analysis(arch, Material()).limit(0.0)
print(f"lambda_0max = {lim.lambda_max:.7f} (the paper: 0.243), kinematic {lim.lambda_kinematic:.7f}")
for k in lim.mechanism.hinges:
    itf = arch.interfaces[k]
    p = lim.mechanism.hinge_points[k]
    edge = "intrados" if np.isclose(np.hypot(p[0], p[2]), 1.0) else "extrados"
    print(f"hinge at joint {arch.names[itf.a]}|{arch.names[itf.b]} on the {edge} (x = {p[0]:+.3f} m, z = {p[2]:.3f} m)")
