"""The departure of a non-linear response from the linear one, split by parity in the load.

For dead loads on a Saint Venant–Kirchhoff body the equilibrium is an analytic function of the
load, ψ(f) = S f + Q(f) + C(f) + …, with Q quadratic, C cubic and so on. A load and its opposite
separate the orders by parity: the part of the departure d(f) = ψ(f) − S f that is *even* in f,
(d(f) + d(−f)) / 2 = Q(f) + (quartic …), is led by the second-order terms — the kinematics of
finite rotation (foreshortening of bent flexures, the coupling of tilt and lift) — and the *odd*
part, (d(f) − d(−f)) / 2 = C(f) + (quintic …), by the third-order ones — the stiffening (or
softening) of flexures that stretch as they bend. :func:`parity_split` computes both from runs at
±f; :func:`parity_summary` states them, like Table 5's errors, as shares of each component's
range.
"""

from __future__ import annotations

import numpy as np

from mechlib.params import check_matrix


def parity_split(plus: object, minus: object, linear_plus: object) -> dict[str, np.ndarray]:
    """Even and odd parts of the departure from linearity, from runs at f and at −f.

    Parameters
    ----------
    plus, minus : array_like (n, k)
        The non-linear responses at the loads f and −f (same units, e.g. µm and µrad).
    linear_plus : array_like (n, k)
        The linear response S f at the loads f (its value at −f is its opposite).

    Returns
    -------
    dict
        ``even`` and ``odd`` (n, k): (d(f) ± d(−f)) / 2 with d the departure ψ − S f;
        ``departure`` (n, k): d(f) = even + odd.

    Raises
    ------
    ValueError
        If the three arrays do not have one shape, or hold non-finite values.
    """
    p = check_matrix("plus", plus)
    m = check_matrix("minus", minus, shape=p.shape)
    lin = check_matrix("linear_plus", linear_plus, shape=p.shape)
    d_plus, d_minus = p - lin, m + lin
    return {
        "even": 0.5 * (d_plus + d_minus),
        "odd": 0.5 * (d_plus - d_minus),
        "departure": d_plus,
    }


def parity_summary(split: dict[str, np.ndarray], scale: object) -> dict[str, np.ndarray]:
    """Largest |part| per component as a share of ``scale`` [%], for each part of
    :func:`parity_split` (``even``, ``odd``, ``departure``).

    Parameters
    ----------
    split : dict
        A result of :func:`parity_split`.
    scale : array_like (k,)
        Each component's range (e.g. its largest |response| over the runs), > 0.

    Raises
    ------
    ValueError
        If a scale is not positive and finite, or has the wrong length.
    """
    s = np.asarray(scale, dtype=float)
    k = split["departure"].shape[1]
    if s.shape != (k,) or not np.all(np.isfinite(s)) or np.any(s <= 0):
        raise ValueError(f"scale must be {k} positive finite values, got {s.tolist()}")
    return {
        name: 100 * np.abs(split[name]).max(axis=0) / s for name in ("even", "odd", "departure")
    }
