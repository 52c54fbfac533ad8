"""The campaign's specification protocol and its registry of families (mechlib.campaign.spec)."""

from __future__ import annotations

import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib import fespecs
from mechlib.campaign import spec as cs
from mechlib.campaign import store as st
from mechlib.campaign.taskcache import model_code_fingerprint
from mechlib.compliant.spec import MechanismSpec
from mechlib.hexflex.spec import ModelSpec
from mechlib.parallelogram.mechanism import layout

PROTOCOL = ("SOLVE_METHOD", "TASK_MODULES", "SOLVER", "quad_order", "n_loads", "mesh", "key",
            "digest", "build", "check_design", "from_key")  # fmt: skip


def test_both_specifications_follow_the_protocol_and_round_trip_through_the_registry() -> None:
    specs = [ModelSpec(SMALL, element="shell", mesh_size=1.0), MechanismSpec(layout(), 10.0, 1)]
    for spec in specs:
        assert all(hasattr(spec, name) for name in PROTOCOL)
        assert cs.spec_from_key(spec.key()) == spec
    assert [cs.family_of(s.key()) for s in specs] == ["hexflex", "mechanism"]
    assert cs.primary() is fespecs.HEXFLEX
    assert st.fingerprints() == {
        "hexflex": model_code_fingerprint(ModelSpec.TASK_MODULES),
        "mechanism": model_code_fingerprint(MechanismSpec.TASK_MODULES),
    }
    assert st.fingerprint() == st.fingerprints()["hexflex"]


def test_the_registry_refuses_a_second_primary_or_unwrapped_family() -> None:
    with pytest.raises(ValueError, match="already the primary one"):
        cs.register(cs.Family("other", ModelSpec, wrapped=True, primary=True))
    with pytest.raises(ValueError, match="already has unwrapped keys"):
        cs.register(cs.Family("other", ModelSpec, wrapped=False))
    assert [f.name for f in cs.families()] == ["hexflex", "mechanism"]
