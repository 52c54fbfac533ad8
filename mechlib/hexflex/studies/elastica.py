"""The reference of the non-linear solver's benchmark: the cantilever's elastica, in closed form.

The inextensible Euler–Bernoulli elastica under a dead end load is a function of
α = PL²/EI only (Bisshopp & Drucker 1945, Q. Appl. Math. 3(3) 272–275): θ'' + α cos θ = 0 on
s ∈ [0, 1], θ(0) = 0, θ'(1) = 0. Its first integral θ'² = 2α (sin θ₀ − sin θ) (θ₀ the tip
rotation) and 1 + sin θ = 2k² sin² φ give, with k² = (1 + sin θ₀)/2 and sin φ₁ = 1/(k√2),

    √α = K(k) − F(φ₁, k),  δ/L = 1 − (2/√α) [E(k) − E(φ₁, k)],  x_tip/L = √(2 sin θ₀ / α)

(SciPy's ``ellipkinc``/``ellipeinc``; θ₀ by Brent's method). :mod:`.cantilever` solves the same
beam as a solid with the non-linear solver the HexFlex's runs use and compares.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

from mechlib.params import check_float

#: Largest load parameter α = PL²/EI accepted (tip rotation ≈ 70°, solved in 5 load steps in
#: 2.3 s on the default beam; the tests use ≤ 2).
MAX_ALPHA = 5.0
#: Bisection and root tolerance of the tip rotation θ₀ [rad] (double-precision round-off).
_ROOT_XTOL = 1e-15


class TipResponse(NamedTuple):
    """Tip of a cantilever under a transverse end load, over the length: deflection δ/L (along
    the load), end shortening (L − x_tip)/L, and the tip rotation θ₀ [rad]."""

    deflection: float
    shortening: float
    rotation: float


def check_alpha(alpha: object) -> float:
    """The load parameter α = PL²/EI as a float in [0, ``MAX_ALPHA``]; ValueError otherwise."""
    return check_float("alpha (PL^2/EI)", alpha, low=0.0, high=MAX_ALPHA)


def elastica_tip(alpha: float) -> TipResponse:
    """Tip (δ/L, (L − x_tip)/L, θ₀ [rad]) of the inextensible elastica cantilever under a dead
    end load, α = PL²/EI in [0, ``MAX_ALPHA``] (closed form; small α: α/3, α²/15, α/2).

    Raises
    ------
    ValueError
        If ``alpha`` is out of range.
    """
    alpha = check_alpha(alpha)
    if alpha == 0.0:
        return TipResponse(0.0, 0.0, 0.0)
    root = math.sqrt(alpha)

    def parts(theta0: float) -> tuple[float, float]:
        m = 0.5 * (1.0 + math.sin(theta0))  # SciPy's parameter m = k²
        return m, math.asin(min(1.0, 1.0 / math.sqrt(2.0 * m)))

    def mismatch(theta0: float) -> float:
        m, phi = parts(theta0)
        return float(ellipk(m) - ellipkinc(phi, m)) - root

    # K − F rises from 0 (θ₀ = 0) to ∞ (θ₀ = π/2): one root in between
    theta0 = brentq(mismatch, 0.0, 0.5 * math.pi * (1.0 - 1e-12), xtol=_ROOT_XTOL)
    m, phi = parts(theta0)
    deflection = 1.0 - 2.0 / root * float(ellipe(m) - ellipeinc(phi, m))
    shortening = 1.0 - math.sqrt(2.0 * math.sin(theta0) / alpha)
    return TipResponse(deflection, shortening, theta0)
