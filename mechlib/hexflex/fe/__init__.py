"""The HexFlex's finite-element model (SfePy, Q2 hexahedra; mm, N, MPa), one instance of the solid
FE core :mod:`mechlib.fe`.

:mod:`.mesh` (planar mesh of the planform, extruded), :mod:`.problem` (the SfePy problem, tabs' load
vectors, clamped region), :mod:`.model` (the linear model, factorised once, compliance in the
thesis's units; it provides what :class:`mechlib.fe.protocol.SolidModel` names, so the core's
non-linear solver runs on it), :mod:`.lean` (the lean model: a coarser mesh with the default
model's pose definition). Imports :mod:`mechlib.fe`, :mod:`mechlib.blas`,
:mod:`mechlib.hexflex.geometry` and :mod:`mechlib.params` only, so that the sources that define an
FE result (the cache's fingerprint, :mod:`mechlib.campaign.sources`) stay few.
"""
