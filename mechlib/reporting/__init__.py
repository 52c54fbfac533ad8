"""What a notebook records and how the book reports it, in one room.

- :mod:`~mechlib.reporting.records`: the :class:`~mechlib.reporting.records.Recorder` a notebook
  records its key numbers through (value, tolerance, glue, report row);
- :mod:`~mechlib.reporting.report`: report rows (comparison, claim, computed) and their verdicts;
- :mod:`~mechlib.reporting.categories`: the verdict categories a row is counted in;
- :mod:`~mechlib.reporting.claims`: the claims registry — every claim the book judges, with the
  records its verdict is computed from and the rule — so that a verdict is written once;
- :mod:`~mechlib.reporting.tables`: reader tables, the thesis's values beside ours.

Science code never imports this room; notebooks and the build wing do.
"""
