"""Compliances as cached campaign tasks: the model's own numbers, read back from the cache."""

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.campaign import experiments as ex
from mechlib.hexflex import compliance as cc
from mechlib.hexflex.fe.model import HexFlexModel


def test_cached_compliance_is_the_models_and_is_read_back(tmp_path, monkeypatch) -> None:
    specs = cc.default_specs(young=71700.0, poisson=0.33, element="q2", mesh_fraction=0.8)
    spec = specs(SMALL)
    assert spec.mesh_size == 0.8 * SMALL.narrowest and spec.mesh == "default"
    fresh = cc.compliance(spec, tmp_path)
    model = HexFlexModel(SMALL, mesh_size=0.8 * SMALL.narrowest)
    np.testing.assert_array_equal(fresh, model.compliance())  # one process: bit for bit
    assert len(list(tmp_path.glob("*.npy"))) == 1
    ex.release_models()

    def no_model(spec):  # a cached compliance builds no model
        raise AssertionError(f"built a model for {spec}")

    monkeypatch.setattr(ex, "model_for", no_model)
    np.testing.assert_array_equal(cc.compliance_maker(specs, tmp_path)(SMALL), fresh)


def test_lean_specs_and_refusals() -> None:
    spec = cc.lean_specs(young=71700.0, poisson=0.33, pose_mesh_size=0.2)(SMALL)
    assert (spec.mesh, spec.mesh_size, spec.element) == ("lean", 0.2, "q2")
    assert cc.lean_specs(young=71700.0, poisson=0.33, pose_mesh_size=None)(SMALL).mesh_size is None
    with pytest.raises(ValueError, match="pose_mesh_size"):
        cc.lean_specs(young=71700.0, poisson=0.33, pose_mesh_size=-1.0)
    with pytest.raises(ValueError, match="poisson"):
        cc.lean_specs(young=71700.0, poisson=0.7, pose_mesh_size=None)
    with pytest.raises(ValueError, match="mesh_fraction"):
        cc.default_specs(young=71700.0, poisson=0.33, element="q2", mesh_fraction=0.0)
