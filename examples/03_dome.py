"""A hemispherical dome: its thrust under a radial spreading of the supports, and its lateral limit.

Run: ``python examples/03_dome.py``.
"""

import numpy as np

from tce import Analysis, Material, hemispherical_dome
from tce.structures.dome import radial_settlement, shell_volume

R, t = 5.0, 0.5  # mid-surface radius and thickness (m)
dome = hemispherical_dome(radius=R, thickness=t, sectors=12, courses=6)
print(f"{len(dome.free_indices)} voussoirs, weight {dome.total_weight:.1f} kN "
      f"(exact shell: {20.0 * shell_volume(R, t):.1f} kN; the facetted blocks are inscribed)")

an = Analysis(dome, Material(friction=0.8))
r = an.solve(0.0, settlements=radial_settlement(dome, 0.001))  # every support 1 mm outward
w = r.support_wrenches
c = dome.centroids[list(dome.support_indices), :2]
outward = -(w[:, :2] * c).sum(axis=1) / np.linalg.norm(c, axis=1)  # the dome's push on each support
print(f"{r.status} ({r.model}): outward thrust per support {outward.mean():.3f} kN "
      f"(spread {np.ptp(outward):.1e}), vertical {w[:, 2].mean():.3f} kN")

lim = an.limit(0.0)
print(f"lateral lambda_max along +x: {lim.lambda_max:.5f} ({lim.status}, {len(lim.mechanism.hinges)} hinges, "
      f"{len(lim.mechanism.sliding)} sliding joints)")
