"""The solid FE core every mechanism's model runs on (SfePy, Q2 hexahedra; mm, N, MPa).

:mod:`.sfepy_base` (quadrature, a quiet SfePy, the stiffness of a problem's equations),
:mod:`.factor` (sparse factorisations), :mod:`.nonlinear` with :mod:`.anderson`,
:mod:`.svk_tangent` and :mod:`.sfepy_tl` (total-Lagrangian Saint Venant–Kirchhoff solves),
:mod:`.pose` and :mod:`.finite_pose` (a rigid stage's pose from nodal displacements),
:mod:`.protocol` (what the solver needs of a model). Imports :mod:`mechlib.params` and
:mod:`mechlib.blas` only: a mechanism's model (:mod:`mechlib.hexflex.fe`, :mod:`mechlib.compliant`)
builds on it, never the reverse, so that the sources that define an FE result (the cache's
fingerprint, :mod:`mechlib.campaign.sources`) stay few.
"""
