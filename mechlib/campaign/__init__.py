"""Running many FE tasks: the designs' loads in, poses out, each task computed once — for any
mechanism whose model specification follows :class:`~.spec.Spec`.

:mod:`.spec` states what a campaign needs of a specification (the :class:`~.spec.Spec` protocol)
and keeps the registry of families (the HexFlex's, a compliant layout's: registered by
:mod:`mechlib.fespecs`); :mod:`.experiments` runs a design on a specification — task kinds:
linear blocks, non-linear runs, model sizes, and full-state snapshots for a reduced-order model
— in any ``concurrent.futures`` executor (:mod:`.executors`: local processes or a Dask cluster,
:mod:`.daskworker`) and caches each finished task on disk under a key (:mod:`.taskcache`) that
includes a digest of the FE sources (:mod:`.sources`, :mod:`.codedigest`); :mod:`.store` packs
the tasks a build used into the versioned results store (:mod:`.storefiles`) and reads it back,
:mod:`.solve` is what one task computes (in every key's code digest); :mod:`.cachecheck`
recomputes a seeded sample cold. Imports the solid FE core (:mod:`mechlib.fe`,
:mod:`mechlib.blas`) and the ground floor, never a mechanism package: a specification names its
own model and code.
"""
