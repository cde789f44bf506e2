"""Independent references for the validation tests.

Everything here is written from the definitions in ``docs/conventions.md`` and the paper
(*3D exploration of internal stresses due to lateral loads and foundation movements in a
semicircular arch*), in plain numpy with per-vertex and per-block loops, and imports nothing
from ``tce``: a test compares tce's answer with one of these, so an error in tce's operators
cannot hide behind the same error in its reference.

Modules
-------
geometry
    Interface frames, tributary areas, and closed-form volumes and centroids of boxes, of the
    chord-faced voussoirs of a semicircular arch and of the voussoirs of a hemispherical dome.
operators
    Equilibrium matrix, support-wrench matrix, dead and lateral loads, compliance and the
    contact-law violation, built vertex by vertex.
lp
    The rigid, Heyman (fn >= 0, no friction limit) TCE and lambda_max as linear programs on
    the reference operators, solved by HiGHS (scipy), not by tce's Clarabel.
mechanism
    Kinematic limit analysis of a voussoir arch by enumeration of its 4-hinge mechanisms
    (virtual work with instantaneous centres).
"""
