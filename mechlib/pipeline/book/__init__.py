"""Book tooling: turns executed notebooks and records into the pages of the Jupyter Book.

Nothing here is imported by the notebooks, so a change in this package rebuilds the book without
re-executing them (the Makefile leaves it out of the notebooks' prerequisites).

Modules
-------
artefacts   thesis artefacts ("Table 3", "Figs 6–7"): parsing, the thesis's order, section labels
quoted      the numbers the prose quotes: every glue role must name a recorded value
cells       per-cell rules: fold computation, remove bookkeeping, neutralise machine paths/warnings
reportpage  the reproduction report page and its verdict summary
diagrams    flow diagrams drawn with matplotlib (the thesis's Figs 1 and 9)
methods     the generated pages that show Figs 1 and 9
htmlcheck   static checks of the built HTML (no network requests, no machine paths, links resolve)
browser     the built book opened in headless Chromium from ``file://`` with the network off
explorer    the page "Try the model": the recorded real-time model as a JS literal, page, figure
explorerdraw  its drawing: the stage moved by a pose, as SVG views
explorerpage  its Markdown and interactive HTML
explorercheck the page's JavaScript in headless Chromium against Python's evaluation
"""
