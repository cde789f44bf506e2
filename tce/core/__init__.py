"""The core: operators built once, conic problems, the Clarabel solves and the direct limit analysis.

``material`` the contact law · ``model`` equilibrium, self-weight and lateral loads, support
wrenches, compliance (spatial and exact planar) · ``loads`` load patterns (point and
distributed loads, fixed or scaled) and their right-hand sides · ``conic`` the contact law
as cones and the scaling · ``solve`` the TCE solver · ``limit`` direct lambda_max and its
mechanism · ``resultants`` interface resultants · ``analysis`` one assembly and material,
scene by scene on the model each needs · ``cvx`` the same problem in cvxpy (a cross-check) ·
``pyramid`` friction pyramids (LP bounds).
"""
