"""A planar compliant mechanism of any layout, for chapter 2's FE method: its description and the
checks that refuse a bad one before meshing (:mod:`.layout`), its quad mesh by gmsh extruded to
Q2 hexahedra (:mod:`.planform`), the SfePy problem with its named regions (:mod:`.problem`), and
the factorised linear model and its non-linear solve, which the HexFlex's pose registration,
campaigns and FE cache take as they take the HexFlex's (:mod:`.model`, :mod:`.solver`,
:mod:`.spec`).

Imports: ``layout`` imports only :mod:`mechlib.params`; ``planform`` imports ``layout``;
``problem`` imports both and the solid FE core's SfePy helpers and pose fit (:mod:`mechlib.fe`);
``model`` imports ``problem`` and the core's factorisation; ``solver`` (the core's non-linear
solve with material regions) imports ``model``; ``spec`` imports both. Nothing here imports the
HexFlex, a campaign, a study or the build wing.
"""
