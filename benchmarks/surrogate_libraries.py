"""Measure GP and PCE libraries on a synthetic HexFlex-like map (6 forces in [-1, 1] N -> 6 poses).

How mechlib.surrogates chose its GP and PCE libraries (issue 28). Not part of the tests or of
`make bench`: it needs packages outside environment.lock, in a scratch virtual environment:

    uv venv /tmp/benchvenv --python .venv/bin/python
    uv pip install --python /tmp/benchvenv/bin/python numpy==2.4.6 scipy==1.17.1 \
        scikit-learn==1.9.1 threadpoolctl smt==2.15.0 openturns==1.27.post1 chaospy==4.3.21
    PYTHONPATH=. /tmp/benchvenv/bin/python benchmarks/surrogate_libraries.py [names] [sizes]

Truth: S_T of Eq 8 plus 2 % noise on every entry, plus ~3 % quadratic, ~1 % cubic and a 1 %
sine (non-polynomial) term. Training: LHS random-cd (seed 1) of 30, 100, 300 runs; validation:
1000 uniform runs. Prints fit time, latency per pose (one pose; batched) and the worst max |error|
as % of the component's range (Table 5's convention). BLAS on one thread.
"""

import sys
import time
import warnings

import numpy as np
from scipy.stats import qmc
from threadpoolctl import threadpool_limits

warnings.filterwarnings("ignore")

rng = np.random.default_rng(0)
S = np.array(
    [
        [57.53, 0, 28.76, 0, -28.76, 0],
        [0, 0, 49.82, 0, 49.82, 0],
        [0, 287.66, 0, 287.66, 0, 287.66],
        [0, 39313.03, 0, -19679.85, 0, -19633.3],
        [0, 0, 0, -34032.01, 0, 34060.19],
        [-3101.84, 0, 3101.79, 0, -3101.81, 0],
    ]
)
S = S + 0.02 * np.abs(S).max(axis=1, keepdims=True) * rng.standard_normal(S.shape)  # full matrix
Q = rng.standard_normal((6, 6, 6))
C = rng.standard_normal((6, 6, 6, 6))
scale = np.abs(S).sum(axis=1)


def truth(x):
    lin = x @ S.T
    quad = np.einsum("oij,ni,nj->no", Q, x, x) / 36 * 0.03 * scale
    cub = np.einsum("oijk,ni,nj,nk->no", C, x, x, x) / 216**0.5 / 6 * 0.01 * scale
    W = np.random.default_rng(3).standard_normal((6, 6))
    smooth = np.sin(0.7 * x @ W.T) * 0.01 * scale
    return lin + quad + cub + smooth


def design(n, seed=1):
    return 2 * qmc.LatinHypercube(d=6, optimization="random-cd", seed=seed).random(n) - 1


Xv = 2 * np.random.default_rng(7).random((1000, 6)) - 1
Yv = truth(Xv)


def err(yp):
    return float((100 * np.abs(yp - Yv).max(0) / np.abs(Yv).max(0)).max())


def sk_gp(X, Y):
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

    ms = []
    for j in range(6):
        k = ConstantKernel(1.0) * RBF(np.ones(6), (1e-2, 1e3)) + WhiteKernel(1e-6, (1e-12, 1e-1))
        ms.append(
            GaussianProcessRegressor(
                k, normalize_y=True, n_restarts_optimizer=2, random_state=0
            ).fit(X, Y[:, j])
        )
    return lambda x: np.column_stack([m.predict(x) for m in ms])


def sk_gp_lin(X, Y):
    # GP on residual of linear LSQ (universal-kriging-like)
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

    A = np.c_[np.ones(len(X)), X]
    B = np.linalg.lstsq(A, Y, rcond=None)[0]
    R = Y - A @ B
    ms = []
    for j in range(6):
        k = ConstantKernel(1.0) * RBF(np.ones(6), (1e-2, 1e3)) + WhiteKernel(1e-8, (1e-14, 1e-1))
        ms.append(
            GaussianProcessRegressor(
                k, normalize_y=True, n_restarts_optimizer=2, random_state=0
            ).fit(X, R[:, j])
        )
    return lambda x: np.c_[np.ones(len(x)), x] @ B + np.column_stack([m.predict(x) for m in ms])


def smt_krg(X, Y, poly="constant"):
    from smt.surrogate_models import KRG

    ms = []
    for j in range(6):
        m = KRG(poly=poly, theta0=[1e-1] * 6, print_global=False, seed=0)
        m.set_training_values(X, Y[:, j])
        m.train()
        ms.append(m)
    return lambda x: np.column_stack([m.predict_values(x)[:, 0] for m in ms])


def smt_krg_multi(X, Y, poly="linear"):
    from smt.surrogate_models import KRG

    m = KRG(poly=poly, theta0=[1e-1] * 6, print_global=False, seed=0)
    m.set_training_values(X, Y)
    m.train()
    return lambda x: m.predict_values(x)


def ot_gp(X, Y):
    import openturns as ot

    ot.Log.Show(ot.Log.NONE)
    ms = []
    for j in range(6):
        cov = ot.SquaredExponential([1.0] * 6, [1.0])
        basis = ot.LinearBasisFactory(6).build()
        fitter = ot.GaussianProcessFitter(ot.Sample(X), ot.Sample(Y[:, [j]]), cov, basis)
        fitter.run()
        reg = ot.GaussianProcessRegression(fitter.getResult())
        reg.run()
        ms.append(reg.getResult().getMetaModel())
    return lambda x: np.column_stack([np.asarray(m(ot.Sample(x)))[:, 0] for m in ms])


def ot_pce(X, Y, degree=3):
    import openturns as ot

    ot.Log.Show(ot.Log.NONE)
    dist = ot.JointDistribution([ot.Uniform(-1, 1)] * 6)
    basis = ot.OrthogonalProductPolynomialFactory([ot.LegendreFactory()] * 6)
    enum = basis.getEnumerateFunction()
    size = enum.getBasisSizeFromTotalDegree(degree)
    adapt = ot.FixedStrategy(basis, size)
    sel = ot.LeastSquaresMetaModelSelectionFactory(ot.LARS(), ot.CorrectedLeaveOneOut())
    proj = ot.LeastSquaresStrategy(ot.Sample(X), ot.Sample(Y), sel)
    algo = ot.FunctionalChaosAlgorithm(ot.Sample(X), ot.Sample(Y), dist, adapt, proj)
    algo.run()
    m = algo.getResult().getMetaModel()
    return lambda x: np.asarray(m(ot.Sample(x)))


def cp_pce(X, Y, degree=3, lars=True):
    import chaospy as cp
    from sklearn import linear_model as lm

    dist = cp.J(*[cp.Uniform(-1, 1) for _ in range(6)])
    exp = cp.generate_expansion(degree, dist)
    model = lm.LarsCV(fit_intercept=False, cv=5) if lars else None
    fs = [cp.fit_regression(exp, X.T, Y[:, j], model=model) for j in range(Y.shape[1])]
    return lambda x: np.column_stack([np.asarray(f(*x.T)) for f in fs])


def cubic_ls(X, Y):
    from sklearn.preprocessing import PolynomialFeatures

    p = PolynomialFeatures(3)
    A = p.fit_transform(X)
    B = np.linalg.lstsq(A, Y, rcond=None)[0]
    return lambda x: p.transform(x) @ B


def quad_ls(X, Y):
    from sklearn.preprocessing import PolynomialFeatures

    p = PolynomialFeatures(2)
    A = p.fit_transform(X)
    B = np.linalg.lstsq(A, Y, rcond=None)[0]
    return lambda x: p.transform(x) @ B


def lin_ls(X, Y):
    B = np.linalg.lstsq(X, Y, rcond=None)[0]
    return lambda x: x @ B


def ml(fam):
    from mechlib import surrogates as sg

    def fit(X, Y):
        m = sg.fit_surrogate(fam, X, Y, amplitude=1.0, seed=0)
        from mechlib.surrogates.families import predict_array

        return lambda x: predict_array(m, x)

    return fit


cands = {
    "ml_gp": ml("gp"),
    "ml_pce": ml("pce"),
    "ml_cubic": ml("cubic"),
    "linear": lin_ls,
    "quadratic": quad_ls,
    "cubic": cubic_ls,
    "sk_gp": sk_gp,
    "sk_gp_linres": sk_gp_lin,
    "smt_krg_const": smt_krg,
    "smt_krg_lin": lambda X, Y: smt_krg(X, Y, "linear"),
    "smt_krg_lin_multi": smt_krg_multi,
    "ot_gp_lin": ot_gp,
    "ot_pce_lars3": ot_pce,
    "cp_pce_lars3": cp_pce,
    "cp_pce_ls3": lambda X, Y: cp_pce(X, Y, 3, False),
}
only = sys.argv[1].split(",") if len(sys.argv) > 1 else list(cands)
ns = [int(a) for a in sys.argv[2].split(",")] if len(sys.argv) > 2 else [30, 100, 300]
with threadpool_limits(1, "blas"):
    for name in only:
        for n in ns:
            X = design(n)
            Y = truth(X)
            try:
                t0 = time.perf_counter()
                f = cands[name](X, Y)
                tf = time.perf_counter() - t0
                yp = f(Xv)
                x1 = Xv[:1]
                reps = 50
                t0 = time.perf_counter()
                for _ in range(reps):
                    f(x1)
                t1 = (time.perf_counter() - t0) / reps * 1e6
                t0 = time.perf_counter()
                f(Xv)
                tb = (time.perf_counter() - t0) / len(Xv) * 1e6
                print(
                    f"{name:18s} n={n:3d} fit={tf:7.2f}s single={t1:9.1f}us "
                    f"batch={tb:8.2f}us/pose maxrange%={err(yp):.4g}",
                    flush=True,
                )
            except Exception as e:
                print(f"{name:18s} n={n:3d} FAILED {type(e).__name__}: {str(e)[:100]}", flush=True)
