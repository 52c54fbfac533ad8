"""The hyper-reduced reduced-order model (ROM) of the geometrically non-linear HexFlex.

:mod:`.basis` (static modes, modal derivatives, optional POD), :mod:`.ecsw` (energy-conserving
sampling and weighting of the elements), :mod:`.tensors` (the reduced internal force as exact
polynomials), :mod:`.model` (the ROM: build, solve, predict poses) and :mod:`.snapshots` (full
non-linear fields of a force design, cached, to train it). Imports the solid FE core
(:mod:`mechlib.fe`, :mod:`mechlib.blas`), :mod:`mechlib.hexflex.fe` and
:mod:`mechlib.campaign`.
"""
