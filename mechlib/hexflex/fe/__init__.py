"""The HexFlex's finite-element model (SfePy, Q2 hexahedra; mm, N, MPa).

:mod:`.mesh` (planar mesh of the planform, extruded), :mod:`.problem` (the SfePy problem, tabs' load
vectors, clamped region), :mod:`.model` (the linear model, factorised once, compliance in the
thesis's units), :mod:`.factor` (sparse factorisations), :mod:`.nonlinear` with :mod:`.anderson`,
:mod:`.svk_tangent` and :mod:`.sfepy_tl` (total-Lagrangian Saint Venant–Kirchhoff solves),
:mod:`.pose` and :mod:`.finite_pose` (the stage's pose from nodal displacements), :mod:`.lean` (the
lean model: a coarser mesh with the default model's pose definition). Imports
:mod:`mechlib.hexflex.geometry` and :mod:`mechlib.params` only, so that the sources that define an
FE result (the cache's fingerprint, :mod:`mechlib.hexflex.campaign.sources`) stay few.
"""
