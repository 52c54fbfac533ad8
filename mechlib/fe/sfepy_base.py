"""What every SfePy solid problem of this library shares: the quadrature order of the Q2 terms,
SfePy kept quiet, its quadrature, and the stiffness of a problem's own equations at zero
displacement. Imports nothing of mechlib: the HexFlex's problem (:mod:`mechlib.hexflex.fe.problem`)
and a compliant layout's (:mod:`mechlib.compliant.problem`) build on it.
"""

from __future__ import annotations

import numpy as np

#: Quadrature order of the Q2 solid terms.
QUAD_ORDER = 4


def quiet_sfepy() -> None:
    """Silence SfePy's console output, including the notice its term modules print on import
    when the optional jax package is absent (jax-based terms are not used here)."""
    import contextlib
    import io

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        import sfepy.terms  # noqa: F401  (imported once, here, for its side effect only)
        from sfepy.base.base import output

    output.set_output(quiet=True)


def integral(order: int = QUAD_ORDER):
    """SfePy quadrature of the given order."""
    from sfepy.discrete import Integral

    return Integral("i", order=order)


def assemble_stiffness(pb, n_dofs: int):
    """The tangent (= linear stiffness) matrix of SfePy problem ``pb``'s own equations at zero
    displacement, reduced to its ``n_dofs`` free DOFs (a copy)."""
    pb.time_update(create_matrix=True)
    pb.get_variables().init_state()
    pb.update_materials()
    return pb.get_evaluator().eval_tangent_matrix(np.zeros(n_dofs)).copy()
