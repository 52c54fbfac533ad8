"""Named tolerances of the parallelogram flexure: our FE, the elastica, and the meta-models
fitted to our FE.
"""

from __future__ import annotations
