"""What the HexFlex chapters compute from the FE model: one study a module.

:mod:`.convergence` (mesh and element convergence of the compliance), :mod:`.beamcheck` (one flexure
against Timoshenko beam theory), :mod:`.cantilever` (the non-linear solver against the elastica of
:mod:`.elastica`), :mod:`.linearity` (where the linear model stops holding), :mod:`.departure` (the
non-linear departure split by parity in the load), :mod:`.family` (members of Eq 8's family at
other thicknesses) and :mod:`.leanmesh` (the lean mesh against the default one on non-linear
runs). Imports the solid FE core (:mod:`mechlib.fe`, :mod:`mechlib.blas`),
:mod:`mechlib.hexflex.fe`, :mod:`mechlib.campaign` and the top of :mod:`mechlib.hexflex`;
nothing below imports a study.
"""
