"""SfePy's total-Lagrangian Saint Venant–Kirchhoff term on a Q2 solid model, consistent tangent.

SfePy 2026.3's ``dw_tl_he_svk`` term doubles the shear *rows* of its tangent modulus, so its
tangent is not the derivative of its residual (Newton then converges only linearly, at rate ½).
:func:`register_svk_term` adds ``dw_tl_he_svk_consistent``, the same residual with the consistent
tangent; ``tests/test_hexflex.py`` checks it against finite differences of the residual.
:func:`tl_evaluator` evaluates either term on a model's field and clamp. The solver's default
tangent and residual (:mod:`mechlib.fe.svk_tangent`) compute the same numbers batched; this
module is their reference (tests, ``make bench``) and the solver's ``tangent="sfepy"``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mechlib.fe import sfepy_base as fe

if TYPE_CHECKING:
    from mechlib.fe.protocol import SolidModel


def tl_evaluator(model: SolidModel, term: str):
    """SfePy evaluator (residual, tangent) of one total-Lagrangian term taking the linear
    model's elasticity tensor, ``term(s.D, v, u)``, on the model's field and clamp.

    Parameters
    ----------
    model : SolidModel
        A Q2 model.
    term : str
        SfePy term name, e.g. ``"dw_tl_he_svk"`` (the stock term) or the consistent one.
    """
    from sfepy.discrete import Equation, Equations, FieldVariable, Material, Problem
    from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
    from sfepy.terms import Term

    if model.element != "q2":
        raise ValueError(f"element must be 'q2' for a TL term, got {model.element!r}")
    p = model.fe
    mat = Material("s", D=stiffness_from_youngpoisson(3, model.young, model.poisson))
    # variables of its own: SfePy caches the TL family data (F, E, ...) on the variable, and an
    # evaluator sharing it with another one was measured returning the other's residual
    u = FieldVariable("u", "unknown", p.field)
    v = FieldVariable("v", "test", p.field, primary_var_name="u")
    t = Term.new(f"{term}(s.D, v, u)", fe.integral(), p.omega, s=mat, v=v, u=u)
    pb = Problem("hexflex_tl", equations=Equations([Equation("balance", t)]))
    pb.set_bcs(ebcs=p.pb.ebcs)
    pb.time_update(create_matrix=True)
    pb.get_variables().init_state()
    pb.update_materials()
    return pb.get_evaluator()


def register_svk_term() -> str:
    """Register (once) and name SfePy's TL Saint Venant–Kirchhoff term with a consistent tangent.

    The stress is SfePy's own (``S = D : E`` with the Voigt-shear convention of its Green strain).
    SfePy's element tangent already accounts for that convention, so the tangent modulus is ``D``
    itself; the stock term doubles its shear rows again (see the module docstring). The stock
    term's tangent also takes its stress from the last *residual* evaluation, at whatever state
    that was; this one computes it at the state of the tangent.
    """
    from sfepy.terms import term_table
    from sfepy.terms.terms_hyperelastic_tl import SaintVenantKirchhoffTLTerm

    name = "dw_tl_he_svk_consistent"
    if name not in term_table:

        class ConsistentSVKTerm(SaintVenantKirchhoffTLTerm):
            def tan_mod_function(self, out, mat, *fargs, **kwargs):
                out[:] = mat
                return out

            def get_fargs(
                self, mat, virtual, state, mode=None, term_mode=None, diff_var=None, **kwargs
            ):
                # SfePy's tangent reuses the stress of the *last residual evaluated*, wherever
                # that was; a tangent at another state would mix two states. Recompute it.
                if diff_var is not None:
                    self.stress_cache = None
                return super().get_fargs(mat, virtual, state, mode, term_mode, diff_var, **kwargs)

        ConsistentSVKTerm.name = name
        term_table[name] = ConsistentSVKTerm
    return name
