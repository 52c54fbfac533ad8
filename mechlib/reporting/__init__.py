"""What a notebook records and how the book reports it, in one room.

- :mod:`~mechlib.reporting.records`: the :class:`~mechlib.reporting.records.Recorder` a notebook
  records its key numbers through (value, tolerance, glue, report row);
- :mod:`~mechlib.reporting.recordplan`: a record plan's entry per key and the plan's checks;
- :mod:`~mechlib.reporting.recordglue`: a plan entry's glue (names, indices, extremes, functions);
- :mod:`~mechlib.reporting.recordhelpers`: the recorder's shorthands (mapping, constants, data);
- :mod:`~mechlib.reporting.jsonready`: JSON-ready copies of recorded values;
- :mod:`~mechlib.reporting.plans`: one record plan per notebook, and the recorder built from it;
- :mod:`~mechlib.reporting.tolerance`: a tolerance, its bounds and why a re-run stays within;
- :mod:`~mechlib.reporting.tolerances`: the named tolerances, one module per kind of numerics;
- :mod:`~mechlib.reporting.report`: report rows (comparison, claim, computed) and their verdicts;
- :mod:`~mechlib.reporting.categories`: the verdict categories a row is counted in;
- :mod:`~mechlib.reporting.claims`: the claims registry — every claim the book judges, with the
  records its verdict is computed from and the rule — so that a verdict is written once;
- :mod:`~mechlib.reporting.tables`: reader tables, the thesis's values beside ours.

Science code never imports this room; notebooks and the build wing do.
"""
