"""The build wing: from notebooks to a checked book. Nothing in the science wing (the rest of
``mechlib``) imports it, so a change here re-executes no notebook (the Makefile leaves it out of
the notebooks' prerequisites); ``tests/test_wings.py`` checks both.

One command line, ``python -m mechlib.pipeline <command>`` (:mod:`~mechlib.pipeline.cli`), is
what the Makefile calls.

Modules
-------
chapters    the chapters' order and the inputs one takes from another's record (declared once)
execute     the one papermill command line; one notebook executed with its chapter inputs
papermillrun  papermill's command line as the build runs it (the kernel's log at ERROR level)
parameters  a notebook's parameter names and the papermill arguments that set them
runs        ``make run``: one notebook with new parameters into ``build/runs``
rerun       ``make rerun`` and the determinism check (byte-identical records, cold)
references  records against ``tests/references``; ``make references``
bookbuild   the book's generated pages (chapters, report, Figs 1 and 9)
book/       the book build's parts: cell rules, report page, diagrams, HTML and browser checks
verdicts    report rows read back from records: categories, counts, roll-up per thesis artefact
landing     the landing page, generated from the records
pagecheck   checks of what a page shows: jargon, bare outputs, paths, counts, uncovered artefacts
pdf         ``make pdf``: the single-page build printed by headless Chromium
pdfcheck    ``make check-pdf``: the PDF against its HTML (pages, titles, figures, typeset math)
cli         the command line
"""
