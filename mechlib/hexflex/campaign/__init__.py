"""Running many FE tasks: the designs' forces in, poses out, each task computed once.

:mod:`.experiments` runs a force design on a model specification in any
``concurrent.futures`` executor (:mod:`.executors`: local processes or a Dask cluster) and caches
each finished task on disk under a key (:mod:`.taskcache`) that includes a digest of the FE
sources (:mod:`.sources`); :mod:`.store` packs the tasks a build used into the versioned results
store and reads it back; :mod:`.cachecheck` recomputes a seeded sample cold; :mod:`.compliance`
reads the compliances of identifications as cached tasks. Imports the solid FE core
(:mod:`mechlib.fe`, :mod:`mechlib.blas`), :mod:`mechlib.hexflex.fe`, the compliant layouts
(:mod:`mechlib.compliant`: their tasks run through the same campaigns) and the top of
:mod:`mechlib.hexflex`, never the studies or the ROM.
"""
