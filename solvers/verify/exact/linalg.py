"""Exact linear algebra on object arrays of jets: solve, inv and det by elimination over
the jets (exact_mode.py makes the formulas' np.linalg use them).
"""

import numpy as np


def is_exact(*arrays):
    return any(isinstance(a, np.ndarray) and a.dtype == object for a in arrays)


def _cramer(A, B):
    """A^-1 B = adj(A) B / det(A) for n <= 3: one division, cofactors by Laplace. As
    rational functions (symbolic.py) this stays far smaller than elimination, whose pivots
    nest quotients; as jets it gives tighter degree bounds."""
    n = A.shape[0]
    D = det(A)
    if D == 0:
        raise np.linalg.LinAlgError("singular matrix (exact)")
    if n == 1:
        return np.array([[x / D for x in B[0]]], dtype=object)
    adj = np.empty((n, n), dtype=object)
    for i in range(n):
        for j in range(n):
            minor = np.delete(np.delete(A, i, axis=0), j, axis=1)
            c = _laplace(minor)
            adj[j, i] = c if (i + j) % 2 == 0 else -c
    X = np.empty_like(B)
    for i in range(n):
        for k in range(B.shape[1]):
            acc = 0
            for j in range(n):
                if not _zero_function(B[j, k]) and not _zero_function(adj[i, j]):
                    acc = acc + adj[i, j] * B[j, k]
            X[i, k] = (acc if not isinstance(acc, int) else 0 * D) / D
    return X


def solve(A, b):
    """Cramer's rule up to 3x3, else Gaussian elimination with exact pivots (the first
    nonzero one)."""
    A = np.array(A, dtype=object)
    b = np.array(b, dtype=object)
    n = A.shape[0]
    vec = b.ndim == 1
    B = b.reshape(n, -1).copy()
    if n <= 3:
        X = _cramer(A, B)
        return X[:, 0] if vec else X
    A = A.copy()
    for c in range(n):
        piv = next((i for i in range(c, n) if A[i, c] != 0), None)
        if piv is None:
            raise np.linalg.LinAlgError("singular matrix (exact)")
        if piv != c:
            A[[c, piv]] = A[[piv, c]]
            B[[c, piv]] = B[[piv, c]]
        inv = 1 / A[c, c]
        for i in range(c + 1, n):
            f = A[i, c] * inv
            # skip only the zero function: a multiplier whose value is zero at the point can
            # still carry a derivative (and a degree) that the elimination must keep
            if not _zero_function(f):
                A[i, c:] = A[i, c:] - f * A[c, c:]
                B[i] = B[i] - f * B[c]
    X = np.empty_like(B)
    for i in range(n - 1, -1, -1):
        s = B[i]
        for j in range(i + 1, n):
            s = s - A[i, j] * X[j]
        X[i] = s / A[i, i]
    return X[:, 0] if vec else X


def inv(A):
    n = np.asarray(A).shape[0]
    return solve(A, np.eye(n, dtype=int).astype(object))


def _zero_function(f) -> bool:
    if isinstance(f, (int, float)):
        return f == 0
    zero = getattr(f, "structural_zero", None)
    if zero is not None:
        return zero()
    parts = getattr(f, "parts", None)          # Radical: both parts the zero function
    if parts is not None:
        return all(p.structural_zero() for p in parts())
    return False


def _laplace(A):
    n = A.shape[0]
    if n == 1:
        return A[0, 0]
    out = 0
    for j in range(n):
        if _zero_function(A[0, j]):
            continue
        minor = np.delete(np.delete(A, 0, axis=0), j, axis=1)
        term = A[0, j] * _laplace(minor)
        out = out + term if j % 2 == 0 else out - term
    return out if not isinstance(out, int) else 0 * A[0, 0]


def det(A):
    """Laplace expansion up to 4x4 (no pivot on a value that is zero only at the point,
    whose derivative elimination would lose), Gaussian elimination above."""
    A = np.array(A, dtype=object).copy()
    n = A.shape[0]
    if n <= 4:
        return _laplace(A)
    out = 1
    for c in range(n):
        piv = next((i for i in range(c, n) if A[i, c] != 0), None)
        if piv is None:
            return 0 * A[0, 0]
        if piv != c:
            A[[c, piv]] = A[[piv, c]]
            out = -out
        out = out * A[c, c]
        inv_ = 1 / A[c, c]
        for i in range(c + 1, n):
            A[i, c:] = A[i, c:] - A[i, c] * inv_ * A[c, c:]
    return out
