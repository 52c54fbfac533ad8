"""Reference evaluator of an exported real-time model, in plain Python (no NumPy).

Shipped as it is in the book's data bundle beside ``realtime_model.json``: ``pose(model, forces)``
evaluates the Legendre polynomial that :mod:`mechlib.metamodels.export` writes, so that anyone can
use the model, or port it, without this library. ``python evaluator.py realtime_model.json``
checks it on the model's own check values.
"""

import json
import math
import sys


def pose(model, forces):
    """Pose [µm, µrad] (x, y, z, θx, θy, θz) of a model dict for six forces [N] in ±amplitude.

    Parameters
    ----------
    model : dict
        As :mod:`mechlib.metamodels.export` writes it: ``amplitude_n``, ``inputs`` (force names),
        ``outputs`` (pose names), ``exponents`` (one degree per force, per term) and ``coef``
        (per term, one coefficient per output) of the basis √(2k+1) P_k(force / amplitude).
    forces : sequence of float
        One force per input [N], each within ±amplitude.

    Returns
    -------
    list of float
        One value per output.

    Raises
    ------
    ValueError
        If a force lies outside ±amplitude (the force is named).

    Examples
    --------
    Two forces of amplitude 2 N and the linear model x = 3 f1, y = 1 + 2 f2 (since
    √3 P_1(f / 2) = √3 f / 2, the coefficients are 2√3 and 4/√3):

    >>> model = {"amplitude_n": 2.0, "inputs": ["f1", "f2"], "outputs": ["x", "y"],
    ...          "exponents": [[0, 0], [1, 0], [0, 1]],
    ...          "coef": [[0.0, 1.0], [2 * math.sqrt(3), 0.0], [0.0, 4 / math.sqrt(3)]]}
    >>> [round(v, 9) for v in pose(model, [1.0, -0.5])]
    [3.0, 0.0]
    >>> pose(model, [2.5, 0.0])
    Traceback (most recent call last):
    ...
    ValueError: force f1 must be within ±2.0 N, got 2.5
    """
    amp, exps = model["amplitude_n"], model["exponents"]
    for name, f in zip(model["inputs"], forces, strict=True):
        if not -amp <= f <= amp:  # the model was validated there only
            raise ValueError(f"force {name} must be within ±{amp} N, got {f}")
    deg = max(max(e) for e in exps)
    basis = []  # per force: √(2k+1) P_k(u), k = 0 .. deg, u = force / amplitude
    for f in forces:
        u, p = f / amp, [1.0, f / amp]
        for k in range(1, deg):
            p.append(((2 * k + 1) * u * p[k] - k * p[k - 1]) / (k + 1))
        basis.append([math.sqrt(2 * k + 1) * p[k] for k in range(deg + 1)])
    out = [0.0] * len(model["outputs"])
    for e, row in zip(exps, model["coef"], strict=True):
        term = 1.0
        for b, k in zip(basis, e, strict=True):
            term *= b[k]
        out = [o + term * c for o, c in zip(out, row, strict=True)]
    return out


if __name__ == "__main__":
    model = json.load(open(sys.argv[1]))
    check = model["check"]
    print(
        max(
            abs(g - e)
            for forces, expected in zip(check["forces_n"], check["poses"], strict=True)
            for g, e in zip(pose(model, forces), expected, strict=True)
        )
    )
