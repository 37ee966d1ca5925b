# symtmm codegen runtime: the fixed kernels of a generated Python evaluator, included
# verbatim before it. Every routine works on a batch of N points at once (numpy
# arrays with the points along the first axis) and needs numpy only.

import numpy as np

# 1/n!, n = 0 .. 63, exact to double: the series of both segment kinds
_IFACT = (
    1.0, 1.0, 0.5, 0.16666666666666666,
    0.041666666666666664, 0.008333333333333333, 0.001388888888888889, 0.0001984126984126984,
    2.48015873015873e-05, 2.7557319223985893e-06, 2.755731922398589e-07, 2.505210838544172e-08,
    2.08767569878681e-09, 1.6059043836821613e-10, 1.1470745597729725e-11, 7.647163731819816e-13,
    4.779477332387385e-14, 2.8114572543455206e-15, 1.5619206968586225e-16, 8.22063524662433e-18,
    4.110317623312165e-19, 1.9572941063391263e-20, 8.896791392450574e-22, 3.868170170630684e-23,
    1.6117375710961184e-24, 6.446950284384474e-26, 2.4795962632247976e-27, 9.183689863795546e-29,
    3.279889237069838e-30, 1.1309962886447716e-31, 3.7699876288159054e-33, 1.216125041553518e-34,
    3.8003907548547434e-36, 1.151633562077195e-37, 3.387157535521162e-39, 9.67759295863189e-41,
    2.6882202662866363e-42, 7.265460179153071e-44, 1.911963205040282e-45, 4.902469756513544e-47,
    1.2256174391283858e-48, 2.9893108271424046e-50, 7.117406731291439e-52, 1.6552108677421951e-53,
    3.7618428812322616e-55, 8.359650847182804e-57, 1.817315401561479e-58, 3.866628513960594e-60,
    8.055476070751236e-62, 1.643974708316579e-63, 3.287949416633158e-65, 6.446959640457172e-67,
    1.2397999308571486e-68, 2.3392451525606576e-70, 4.331935467704922e-72, 7.876246304918039e-74,
    1.4064725544496498e-75, 2.4674957095607893e-77, 4.254302947518602e-79, 7.2106829618959365e-81,
    1.2017804936493226e-82, 1.9701319568021682e-84, 3.1776321883905942e-86, 5.043860616493007e-88,
)


def _steps(nu, nu_step):
    """Per point, the steps of ``|beta| l <= nu_step`` for a segment with ``nu = |beta| l``."""
    n = np.ceil(np.where(np.isfinite(nu), nu, 0.0) / nu_step)
    return np.maximum(n, 1).astype(int)


def _units(b, EI, L):
    """Units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L, shape (N, 4)."""
    b = np.maximum(b, 1 / L)
    return np.stack([np.ones_like(b), 1 / b, 1 / (EI * b**2), 1 / (EI * b**3)], axis=-1)


def _orthonormalise(E, logscale):
    """E := Q of E = Q F (Householder), and logscale + log det F."""
    E, F = np.linalg.qr(E)
    return E, logscale + np.sum(np.log(np.diagonal(F, axis1=-2, axis2=-1)), axis=-1)


# Euler-Bernoulli segments: the transfer matrix from the entire functions
# c_j(x) = sum_k x^k / (4k+j)!, x = -lam^2 m l^4/EI, with no branch to choose and
# no 0/0 at lam = 0.

def _cfun(x):
    """c_0..c_3 of a complex array x: series below |x| = 1, closed forms above."""
    small = np.abs(x) < 1.0
    out = [np.empty_like(x) for _ in range(4)]
    if small.any():
        xs = x[small]
        for j in range(4):
            acc = np.zeros_like(xs)
            for k in reversed(range(16)):       # 1/(4k+j)! < 1e-80 beyond
                acc = acc * xs + _IFACT[4 * k + j]
            out[j][small] = acc
    big = ~small
    if big.any():
        nu = x[big] ** 0.25
        ch, co, sh, si = np.cosh(nu), np.cos(nu), np.sinh(nu), np.sin(nu)
        out[0][big] = (ch + co) / 2
        out[1][big] = (sh + si) / (2 * nu)
        out[2][big] = (ch - co) / (2 * nu**2)
        out[3][big] = (sh - si) / (2 * nu**3)
    return out


def _segment(lam2, a, length, EI, n):
    """Transfer matrices of one of n equal steps of an Euler-Bernoulli segment, (N, 4, 4).

    ``a = m length^4 / EI`` (``lam2`` shifted by kw/m on a foundation); I for length 0.
    """
    if length == 0:
        return np.broadcast_to(np.eye(4, dtype=complex), lam2.shape + (4, 4))
    x = -lam2 * (a / n**4)
    c0, c1, c2, c3 = _cfun(x)
    h = length / n
    rows = [[c0, h * c1, h**2 * c2 / EI, h**3 * c3 / EI],
            [x * c3 / h, c0, h * c1 / EI, h**2 * c2 / EI],
            [EI * x * c2 / h**2, EI * x * c3 / h, c0, h * c1],
            [EI * x * c1 / h**3, EI * x * c2 / h**2, x * c3 / h, c0]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


# Beam theories other than the plain Euler-Bernoulli one: axial force N, rotary
# inertia rhoI, shear stiffness kGA, a foundation kw, as symtmm.elements.theories
# computes them. A theory is th = (EI, a, b, cN, rhoI, m, kw): c = cN + rhoI lam2,
# mu = m lam2 + kw.

def _invariants(lam2, th):
    """c, mu and t, d, the trace and determinant of G = B C, of the theory th at lam2."""
    EI, a, b, cN, rhoI, m, kw = th
    c = cN + rhoI * lam2
    mu = m * lam2 + kw
    return c, mu, c / EI - b * mu, mu * (a * a - b * c) / EI


def _wave(lam2, th):
    """A bound on the largest wave number |s| of the theory th at lam2 (1/length)."""
    _, _, t, d = _invariants(lam2, th)
    return np.sqrt(np.abs(t) / 2 + np.sqrt(np.abs(t) ** 2 / 4 + np.abs(d)))


def _segment_gen(lam2, th, length, n):
    """exp(A h) of one of n equal steps h of a segment of the theory th, (N, 4, 4).

    In [Y, Theta, M, Q]: alpha, beta of F0 = cosh(s h), F1 = sinh(s h)/s from
    their series in (t, d) on a piece h/2^j with max|r| (h/2^j)^2 <= 1 (over the
    batch), then doubled j times; U = [[F0(G), B F1(G')], [C F1(G), F0(G')]],
    G = B C on (Y, M), G' = C B on (Theta, Q), B = [[a, b], [c, a]],
    C = [[0, 1/EI], [-mu, 0]].
    """
    EI, a, b = th[:3]
    c, mu, t, d = _invariants(lam2, th)
    w = float(np.max(_wave(lam2, th), initial=0.0))
    h, nd = length / n, 0
    while w * h > 1.0:
        h /= 2
        nd += 1
    T, DD = t * h * h, d * (h * h) * (h * h)
    qp, q = np.zeros_like(lam2), np.ones_like(lam2)
    s0a, s0b, s1a, s1b = (np.zeros_like(lam2) for _ in range(4))
    for k in range(1, 14):   # k/(2k)! < 1e-18 beyond: the error for w h <= 1
        s0b = s0b + q * _IFACT[2 * k]
        s0a = s0a + qp * _IFACT[2 * k]
        s1b = s1b + q * _IFACT[2 * k + 1]
        s1a = s1a + qp * _IFACT[2 * k + 1]
        qp, q = q, T * q - DD * qp
    a0, b0 = 1 - DD * s0a, h * h * s0b
    a1, b1 = h * (1 - DD * s1a), h * h * h * s1b
    for _ in range(nd):   # F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1
        a0, b0, a1, b1 = (2 * (a0 * a0 - d * b0 * b0) - 1, 2 * (2 * a0 * b0 + t * b0 * b0),
                          2 * (a0 * a1 - d * b0 * b1), 2 * (a0 * b1 + a1 * b0 + t * b0 * b1))
    g00, g01, g10, g11 = -b * mu, a / EI, -a * mu, c / EI     # G = B C, on (Y, M)
    p00, p01, p10, p11 = c / EI, a / EI, -mu * a, -mu * b     # G' = C B, on (Theta, Q)
    h00, h01, h10, h11 = a1 + b1 * p00, b1 * p01, b1 * p10, a1 + b1 * p11   # F1(G')
    k00, k01, k10, k11 = a1 + b1 * g00, b1 * g01, b1 * g10, a1 + b1 * g11   # F1(G)
    U = np.empty(lam2.shape + (4, 4), dtype=complex)
    U[..., 0, 0], U[..., 0, 2] = a0 + b0 * g00, b0 * g01
    U[..., 2, 0], U[..., 2, 2] = b0 * g10, a0 + b0 * g11
    U[..., 1, 1], U[..., 1, 3] = a0 + b0 * p00, b0 * p01
    U[..., 3, 1], U[..., 3, 3] = b0 * p10, a0 + b0 * p11
    U[..., 0, 1], U[..., 0, 3] = a * h00 + b * h10, a * h01 + b * h11
    U[..., 2, 1], U[..., 2, 3] = c * h00 + a * h10, c * h01 + a * h11
    U[..., 1, 0], U[..., 1, 2] = k10 / EI, k11 / EI
    U[..., 3, 0], U[..., 3, 2] = -mu * k00, -mu * k01
    return U


# Beams joined by continuous layers: one member of nb beams whose transfer matrix is
# the single beam's with the scalar x replaced by the nb x nb matrix
# X = -(diag(A lam^2 + F) + K + lam C) (symtmm.elements.layer): blocks c_j(X) above
# the diagonal and X c_j(X) below, in the state Y_1..Y_nb, Theta_1.., M_1.., Q_1..
# The member's constants cp: l, A (nb), F (nb), K (nb x nb), C (nb x nb), l^2/EI (nb),
# l^3/EI (nb); K and C are the layers' Laplacians times l^4/EI, row by row.

def _coupled_parts(cp, nb):
    v = np.asarray(cp, dtype=float)
    K = v[1 + 2 * nb:1 + 2 * nb + nb * nb].reshape(nb, nb)
    C = v[1 + 2 * nb + nb * nb:1 + 2 * nb + 2 * nb * nb].reshape(nb, nb)
    rest = v[1 + 2 * nb + 2 * nb * nb:]
    return v[0], v[1:1 + nb], v[1 + nb:1 + 2 * nb], K, C, rest[:nb], rest[nb:2 * nb]


def _coupled_x(lam, lam2, A, F, K, C):
    """X at every point, (N, nb, nb)."""
    nb = len(A)
    X = K + lam[..., None, None] * C
    idx = np.arange(nb)
    X = X + np.zeros(lam2.shape + (1, 1), dtype=complex)
    X[..., idx, idx] += lam2[..., None] * A + F
    return -X


def _wave_coupled(lam2, cp, nb):
    """|beta| l of the member per point: the fourth root of the infinity norm of X
    (|lam| taken as sqrt|lam2|)."""
    _, A, F, K, C, _, _ = _coupled_parts(cp, nb)
    idx = np.arange(nb)
    M = np.abs(K + np.zeros(lam2.shape + (1, 1), dtype=complex))
    D = np.abs(K[idx, idx] + lam2[..., None] * A + F)
    M[..., idx, idx] = D
    M = M + np.abs(C) * np.sqrt(np.abs(lam2))[..., None, None]
    return np.max(np.sum(M, axis=-1), axis=-1) ** 0.25


def _segment_coupled(lam, lam2, cp, nb, n):
    """Transfer matrices of one of n equal steps of the member, (N, 4 nb, 4 nb)
    (|X| <= nu_step^4 = 256 per step: 11 terms, the rest below 1e-27); I for l = 0."""
    length, A, F, K, C, sM, sQ = _coupled_parts(cp, nb)
    m = 4 * nb
    if length == 0:
        return np.broadcast_to(np.eye(m, dtype=complex), lam2.shape + (m, m))
    X = _coupled_x(lam, lam2, A, F, K, C) / n**4
    eye = np.broadcast_to(np.eye(nb, dtype=complex), X.shape)
    c = [_IFACT[q] * eye for q in range(4)]
    P = eye
    for k in range(1, 11):
        P = P @ X
        c = [c[q] + _IFACT[4 * k + q] * P for q in range(4)]
    # the scaled state (Y, h Theta, h^2 M/EI, h^3 Q/EI) back to (Y, Theta, M, Q)
    h = length / n
    s = [np.ones(nb), np.full(nb, h), sM / n**2, sQ / n**3]
    U = np.empty(lam2.shape + (m, m), dtype=complex)
    for a in range(4):
        for b in range(4):
            V = c[b - a] if b >= a else X @ c[4 + b - a]
            U[..., a * nb:(a + 1) * nb, b * nb:(b + 1) * nb] = V * (s[b][None, :] / s[a][:, None])
    return U
