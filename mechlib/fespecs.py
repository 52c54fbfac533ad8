"""The families of FE specifications this repository's campaigns, FE cache and results store
hold, entered in :mod:`mechlib.campaign.spec`'s registry: the HexFlex's
:class:`~mechlib.hexflex.spec.ModelSpec` (the primary family, whose keys are its fields) and a
compliant layout's :class:`~mechlib.compliant.spec.MechanismSpec` (keys ``{"mechanism": …}``).

Whatever reads or writes a results store, or recomputes cached tasks cold, imports this module
first (the build wing's store and re-run commands, their tests); the campaign package itself
names no family. The names are those of the stores' manifests (their ``fingerprints``).
"""

from __future__ import annotations

from mechlib.campaign.spec import Family, register
from mechlib.compliant.spec import MechanismSpec
from mechlib.hexflex.spec import ModelSpec

#: the HexFlex's tasks: six actuator forces; its fingerprint is also a store's ``fingerprint``
HEXFLEX = register(Family("hexflex", ModelSpec, wrapped=False, primary=True))
#: a compliant layout's tasks: one column per load port
MECHANISM = register(Family("mechanism", MechanismSpec, wrapped=True))
