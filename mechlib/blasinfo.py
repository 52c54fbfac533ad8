"""Which BLAS kernel this process computes with (not part of any FE task's code: reading it
never changes a result, so it lives apart from :mod:`mechlib.blas`, whose source the FE results'
cache keys digest)."""

from __future__ import annotations


def openblas_kernel() -> str:
    """The kernel OpenBLAS chose for this process (threadpoolctl's ``architecture``: e.g.
    ``Haswell``, ``SkylakeX``, ``Sandybridge``), the distinct names of every loaded OpenBLAS
    joined by ``+``; ``none`` without OpenBLAS.

    ``OPENBLAS_CORETYPE`` overrides OpenBLAS's choice, so the same machine can compute with
    another machine's kernel (and round-off).
    """
    from threadpoolctl import threadpool_info

    names = {i.get("architecture") or "unknown" for i in threadpool_info()
             if i.get("internal_api") == "openblas"}  # fmt: skip
    return "+".join(sorted(names)) or "none"
