"""The paper: lambda_0max and lambda_90max of its arch (printed to three digits).

Source: *3D exploration of internal stresses due to lateral loads and foundation movements in a
semicircular arch* ("the paper", the method tce implements): the arch of inner radius 1.00 m,
thickness 0.20 m, depth 0.25 m, 14 voussoirs, mu = 0.8; lambda_0max = 0.243 (Fig. 8, in-plane)
and lambda_90max = 0.178 (Fig. 9, out-of-plane). tce: 0.242824 (the 4-hinge mechanism worked out
by hand in tests/reference/mechanism.py gives the same) and 0.17876 (the whole arch rocking about
its springing edges, (d/2)/z_c). The discretisation is the paper's own (14 voussoirs), so there
is no convergence to study. Tolerance 1e-3: the printed digits.
"""

import pytest
from _atlas import check_case


@pytest.mark.parametrize("name", ["paper_in_plane", "paper_out_of_plane"])
def test_published_value(name):
    check_case(name)
