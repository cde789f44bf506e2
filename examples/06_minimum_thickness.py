"""Minimum thickness of the semicircular arch under self-weight, towards Milankovitch's t/R = 0.1075.

Bisects the thinnest arch (centreline radius 1 m) that still stands, for a few numbers of
voussoirs. Run: ``python examples/06_minimum_thickness.py [voussoirs ...]`` (default 8 14 30).
"""

import sys

from tce import arch_minimum_thickness

counts = [int(a) for a in sys.argv[1:]] or [8, 14, 30]
for n in counts:
    res = arch_minimum_thickness(centre_radius=1.0, voussoirs=n, tol=1e-5)
    print(f"{n:4d} voussoirs: t/R = {res.ratio:.5f} ({res.n_solves} solves)")
print("Milankovitch (continuous arch): t/R = 0.1075")
