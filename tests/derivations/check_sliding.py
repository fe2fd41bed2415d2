#!/usr/bin/env python3
# Independent on purpose: a test oracle (ctest sympy_*) re-deriving docs/sliding.md in SymPy; it never calls coinroll.
"""Symbolic checks of docs/sliding.md (run with Debian's python3-sympy; about 40 s).

For general M, a, h, rho, I_X, I_Z, g, mu, a general couple tau and a general slip direction, on both
sides sigma = sign(theta) = +-1, in the seed's turning frame XYZ (docs/derivations.md, docs/rim.md):
  (a)  §1  the sliding equations built from scratch (Newton-Euler with the unknowns omega', N, the held
           contact y_G = H(theta) differentiated twice) against the vector forms (1.4)-(1.8); the slip is
           horizontal (1.2); the Delassus form (1.9)-(1.10);
  (b)  §2  dE/dt = -mu N |s| + tau . omega along them (2.1), the horizontal velocity's equations from
           Newton's law in the turning frame;
  (c)  §3  Painleve: Sherman-Morrison (3.1)-(3.2), the closed form (3.3) of D, D / M = y . W (y - mu s)
           (3.4), the thresholds (3.5)-(3.6) (thin disk sqrt(5)/2 at 24.09 deg, Painleve's rod 4/3), and
           numerically the thick coins' (the toy's 1.1225 and 1.1349) with the solid's own I_X,
           N sees a couple only through tau_X (6.2);
  (d)  §4  the switch: the rolling solution satisfies the sliding equations with mu s_hat = -F_roll / N_roll
           (4.4), N's sensitivity (4.2), the condensed compliance W_c is diagonal in (e_X, h) with (4.3),
           mu_k < mu_s gives (4.5)-(4.6), and the quadratic start (4.7)-(4.8) for mu_k = mu_s;
  (e)  §5  the skid of an upright coin: t*, speed after, friction work; rolling after it fits the cone.
Exits non-zero if any identity fails (each failure is printed).
"""
import time

import mpmath
import sympy as sp

from sympy_checks import Claims, numerator_on_circles

started = time.monotonic()
claims = Claims("docs/sliding.md")

M, a, h, rho, g, IX, IZ = sp.symbols("M a h rho g I_X I_Z", positive=True)
mu, Sm = sp.symbols("mu S_m", positive=True)           # friction coefficient, slip speed |s|
wX, wY, wZ = sp.symbols("omega_X omega_Y omega_Z", real=True)
dX, dY, dZ, N = sp.symbols("domega_X domega_Y domega_Z N", real=True)
U1, U2, dU1, dU2 = sp.symbols("U1 U2 dU1 dU2", real=True)  # horizontal velocity of G along e_X, h
tX, tY, tZ = sp.symbols("tau_X tau_Y tau_Z", real=True)
S, C = sp.symbols("S C")      # sin(theta), cos(theta)
sb, cb = sp.symbols("sb cb")  # slip direction s_hat = cb e_X + sb h
sg, cg = sp.symbols("sg cg")  # rolling friction direction f_hat = cg e_X + sg h


def reduce_(expr):
    """Numerator of expr reduced modulo S^2 + C^2 = 1, sb^2 + cb^2 = 1, sg^2 + cg^2 = 1 (exact)."""
    return numerator_on_circles(expr, [(S, C), (sb, cb), (sg, cg)])


def require(name, expr):
    claims.vanishes(name, reduce_(expr))


def require_all(name, vector):
    for i, component in enumerate(vector):
        require(f"{name} [{i}]", component)


def require_true(name, condition):
    claims.holds(name, condition)


def dth(expr):
    """d/dtheta of an expression in S = sin(theta), C = cos(theta)."""
    return sp.diff(expr, S) * C - sp.diff(expr, C) * S


def dth_vec(v):
    return v.applyfunc(dth)


yhat = sp.Matrix([0, C, -S])          # floor normal in XYZ (rim.md 1.2)
eX = sp.Matrix([1, 0, 0])
hh = sp.Matrix([0, S, C])             # e_X x y_hat: horizontal, perpendicular to e_X (euler_disk 2.9)
omega = sp.Matrix([wX, wY, wZ])
dOmegaSym = sp.Matrix([dX, dY, dZ])   # omega' (component derivative in XYZ)
Omega = sp.Matrix([wX, wY, -wY * S / C])  # the frame's angular velocity (rim.md 2.1)
inertia = sp.diag(IX, IX, IZ)
inertia_inv = sp.diag(1 / IX, 1 / IX, 1 / IZ)
tau = sp.Matrix([tX, tY, tZ])
s_hat = cb * eX + sb * hh
f_hat = cg * eX + sg * hh
f_perp = -sg * eX + cg * hh           # y_hat x f_hat ... the horizontal unit vector perpendicular to f_hat


def geometry(sigma):
    A = a - rho + rho * C
    B = sigma * (h / 2 - rho) + rho * S
    c = sp.Matrix([0, -A, B])                       # rim.md (1.3)
    c_comp = dth_vec(c) * wX                        # component derivative, rim.md (2.3)
    c_floor = c_comp + Omega.cross(c)               # derivative in the floor frame
    H = A * C + B * S                               # height of G, rim.md (1.4)
    Lam = A * S - B * C                             # rim.md (1.7)
    return A, B, c, c_comp, c_floor, H, Lam


def delassus(c):
    """W x = x / M + (I^-1 (c x x)) x c  (1.9), as a matrix."""
    cols = []
    for i in range(3):
        x = sp.zeros(3, 1)
        x[i] = 1
        cols.append(x / M + (inertia_inv * c.cross(x)).cross(c))
    return sp.Matrix.hstack(*cols)


def sliding_from_scratch(sigma):
    """Sliding coin from scratch, N kept as a symbol: Euler about G with R = N (y - mu s_hat) at the contact
    gives omega'(N) (linear in N); Newton's vertical law with the held contact y_G = H(theta), differentiated
    twice, is the residual res(N) = M d2H/dt2 - (N - M g), whose root is the normal force."""
    A, B, c, c_comp, c_floor, H, Lam = geometry(sigma)
    R = N * yhat - mu * N * s_hat
    dOm = inertia_inv * (c.cross(R) + tau - Omega.cross(inertia * omega))
    v_y = dth(H) * wX
    a_y = dth(v_y) * wX + sp.diff(v_y, wX) * dOm[0]
    res = sp.expand(M * a_y - (N - M * g))
    return dOm, res


def normal_force(res):
    """The root of the residual, linear in N."""
    slope = sp.diff(res, N)
    return -res.subs(N, 0) / slope


def rolling_from_scratch(sigma):
    """omega' of a rolling coin (rim.md 2.4-2.7), solved with the block structure (2.8), and R = M a_G + M g y.
    Returns also a_G as a function of the symbols omega' for the kinematic identities."""
    A, B, c, c_comp, c_floor, H, Lam = geometry(sigma)
    v = -omega.cross(c)
    a_G_sym = -(dOmegaSym.cross(c) + omega.cross(c_comp)) + Omega.cross(v)
    m = inertia + M * (c.dot(c) * sp.eye(3) - c * c.T)
    f = (-Omega.cross(inertia * omega) + M * c.cross(Omega.cross(v) - omega.cross(c_comp))
         + M * g * c.cross(yhat) + tau)
    det = m[1, 1] * m[2, 2] - m[1, 2]**2
    d = sp.Matrix([f[0] / m[0, 0], (m[2, 2] * f[1] - m[1, 2] * f[2]) / det, (m[1, 1] * f[2] - m[1, 2] * f[1]) / det])
    R = (M * a_G_sym + M * g * yhat).subs({dX: d[0], dY: d[1], dZ: d[2]})
    return d, R, a_G_sym, m


# ================================================================================ (a) §1
for sigma in (1, -1):
    A, B, c, c_comp, c_floor, H, Lam = geometry(sigma)
    dOm, res = sliding_from_scratch(sigma)
    # (1.2) G's vertical speed from the held contact makes the slip horizontal.
    v_y = dth(H) * wX
    require(f"(1.2) v_G . y = dH/dt = -(omega x c) . y, sigma = {sigma}", v_y + omega.cross(c).dot(yhat))
    require(f"(1.2) ... = -Lambda omega_X, sigma = {sigma}", v_y + Lam * wX)
    # (1.4)-(1.7) vector forms with omega-dot the inertial derivative omega' + Omega x omega. Identities in N:
    # each form minus its claim is a multiple of the vertical residual res(N) (zero at the normal force).
    wdot = dOm + Omega.cross(omega)
    m = c.cross(yhat)
    k = c.cross(yhat - mu * s_hat)
    N0 = M * g - M * omega.cross(c_floor).dot(yhat)
    require_all(f"(1.6) m = c x y = Lambda e_X, sigma = {sigma}", m - Lam * eX)
    require(f"(1.5) vertical law <=> N = N0 - M m . omega-dot, sigma = {sigma}",
            (N - (N0 - M * m.dot(wdot))) + res)
    require(f"(1.5) vertical law <=> N = M (g - (H - rho) omega_X^2 - Lambda omega_X'), sigma = {sigma}",
            (N - M * (g - (H - rho) * wX**2 - Lam * dOm[0])) + res)
    lhs = (inertia + M * k * m.T) * wdot
    rhs = -omega.cross(inertia * omega) + N0 * k + tau
    require_all(f"(1.7) [I_G + M k m^T] omega-dot = -omega x I_G omega + N0 k + tau (+ k res), sigma = {sigma}",
                lhs - rhs + k * res)
    require_all(f"(1.4) I omega-dot + omega x I omega = N k + tau (Euler in the inertial form), sigma = {sigma}",
                inertia * wdot + omega.cross(inertia * omega) - N * k - tau)
    # (1.9)-(1.10): acceleration of the material contact point = W R + b; vertical part 0 = the held contact.
    W = delassus(c)
    require_all(f"(1.9) W is symmetric, sigma = {sigma}", W - W.T)
    R = N * (yhat - mu * s_hat)
    a_G = R / M - g * yhat
    sdot_P = a_G + wdot.cross(c) + omega.cross(c_floor)
    b = -g * yhat + (inertia_inv * (tau - omega.cross(inertia * omega))).cross(c) + omega.cross(c_floor)
    require_all(f"(1.9) s_P-dot = a_G + omega-dot x c + omega x c-dot = W R + b, sigma = {sigma}",
                sdot_P - (W * R + b))
    require(f"(1.10) y . s_P-dot = -res / M: the held contact, sigma = {sigma}", sdot_P.dot(yhat) + res / M)
    require(f"(1.10) N = -y . b / (y . W (y - mu s_hat)) at res = 0, sigma = {sigma}",
            normal_force(res) * (yhat.dot(W * (yhat - mu * s_hat))) + yhat.dot(b))
print(f"       ({time.monotonic() - started:.1f} s)")

# ================================================================================ (b) §2
for sigma in (1, -1):
    A, B, c, c_comp, c_floor, H, Lam = geometry(sigma)
    dOm, res = sliding_from_scratch(sigma)
    v_y = dth(H) * wX
    vG = U1 * eX + U2 * hh + v_y * yhat
    # Floor-frame acceleration: component derivative (theta' = omega_X, omega', U') plus Omega x v_G.
    vG_comp = dth_vec(vG) * wX + sp.diff(vG, wX) * dOm[0] + eX * dU1 + hh * dU2
    a_G = vG_comp + Omega.cross(vG)
    F = -mu * N * s_hat
    sol = sp.solve([M * a_G.dot(eX) - F.dot(eX), M * a_G.dot(hh) - F.dot(hh)], [dU1, dU2], dict=True)[0]
    require(f"(1.8) vertical component of M a_G - R - M g... = res, sigma = {sigma}",
            (M * a_G.dot(yhat) - (N - M * g)).subs(sol) - res)
    require(f"(1.8) the horizontal frame turns at phi' = omega_Y / cos: U1' = F.e_X/M - phi' U2, sigma = {sigma}",
            sol[dU1] - (F.dot(eX) / M - wY / C * U2))
    require(f"(1.8) ... U2' = F.h/M + phi' U1, sigma = {sigma}", sol[dU2] - (F.dot(hh) / M + wY / C * U1))
    energy = M * vG.dot(vG) / 2 + (IX * (wX**2 + wY**2) + IZ * wZ**2) / 2 + M * g * H      # (2.2)
    dE = (dth(energy) * wX + sum(sp.diff(energy, w) * dw for w, dw in zip(omega, dOm))
          + sp.diff(energy, U1) * sol[dU1] + sp.diff(energy, U2) * sol[dU2])
    # State with slip S_m s_hat: U = S_m s_hat - (omega x c)_h. dE/dt - claim = v_y res (0 at the normal force).
    on_slip = {U1: Sm * cb - omega.cross(c).dot(eX), U2: Sm * sb - omega.cross(c).dot(hh)}
    require(f"(2.1) dE/dt = -mu N |s| + tau . omega while sliding, sigma = {sigma}",
            (dE - (-mu * N * Sm + tau.dot(omega)) - v_y * res).subs(on_slip))
print(f"       ({time.monotonic() - started:.1f} s)")

# ================================================================================ (c) §3
for sigma in (1, -1):
    A, B, c, c_comp, c_floor, H, Lam = geometry(sigma)
    dOm, res = sliding_from_scratch(sigma)
    m = c.cross(yhat)
    k = c.cross(yhat - mu * s_hat)
    N0 = M * g - M * omega.cross(c_floor).dot(yhat)
    bvec = -omega.cross(inertia * omega) + tau
    D = 1 + M * (m.T * inertia_inv * k)[0]
    require(f"(3.1) det(I_G + M k m^T) = det(I_G) D, sigma = {sigma}",
            (inertia + M * k * m.T).det() - inertia.det() * D)
    require(f"(3.2) vertical law <=> N D = N0 - M m^T I_G^-1 (tau - omega x I_G omega), sigma = {sigma}",
            N * D - (N0 - M * (m.T * inertia_inv * bvec)[0]) + res)
    require(f"(3.2) the residual's slope is -D: N is unique iff D != 0, sigma = {sigma}", sp.diff(res, N) + D)
    require(f"(3.3) D = 1 + (M / I_X)(Lambda^2 + mu Lambda H (s_hat . h)), sigma = {sigma}",
            D - (1 + M / IX * (Lam**2 + mu * Lam * H * sb)))
    W = delassus(c)
    require(f"(3.4) D / M = y . W (y - mu s_hat), sigma = {sigma}", D / M - yhat.dot(W * (yhat - mu * s_hat)))
    require(f"(3.4) y . W y = 1/M + Lambda^2 / I_X, sigma = {sigma}", yhat.dot(W * yhat) - (1 / M + Lam**2 / IX))
    Nsl = normal_force(res)
    require(f"(6.2) dN/dtau_Y = dN/dtau_Z = 0 while sliding, sigma = {sigma}",
            sp.diff(Nsl, tY)**2 + sp.diff(Nsl, tZ)**2)
    require(f"(6.2) dN/dtau_X = -M Lambda / (I_X D), sigma = {sigma}", sp.diff(Nsl, tX) + M * Lam / (IX * D))

# (3.5)-(3.6): thin coin, s_hat = -h, D = 0 at mu_P(theta) = (k + sin^2) / (sin cos), k = I_X / (M a^2).
kk, t_ = sp.symbols("k t", positive=True)
A, B, c, c_comp, c_floor, H, Lam = geometry(1)
D_thin = (1 + M / IX * (Lam**2 - mu * Lam * H)).subs({h: 0, rho: 0})
muP = (kk + S**2) / (S * C)
require("(3.5) thin coin, s_hat = -h: D = 0 at mu = (k + sin^2 th) / (sin th cos th)",
        D_thin.subs(IX, kk * M * a**2).subs(mu, muP))
# In t = tan(theta): mu_P = k / t + (k + 1) t, least at t = sqrt(k / (k + 1)), value 2 sqrt(k (k + 1)).
muP_t = kk / t_ + (kk + 1) * t_
require("(3.5) mu_P = k / tan + (k + 1) tan", muP - muP_t.subs(t_, S / C))
t_star = sp.sqrt(kk / (kk + 1))
require("(3.6) d mu_P / d tan = 0 at tan = sqrt(k / (k + 1))", sp.simplify(sp.diff(muP_t, t_).subs(t_, t_star)))
require("(3.6) min mu_P = 2 sqrt(k (k + 1))", sp.simplify(muP_t.subs(t_, t_star) - 2 * sp.sqrt(kk * (kk + 1))))
disk_P = 2 * sp.sqrt(sp.Rational(1, 4) * sp.Rational(5, 4))
require_true("(3.6) thin disk (k = 1/4): sqrt(5)/2 at 24.09 deg",
             sp.simplify(disk_P - sp.sqrt(5) / 2) == 0
             and abs(float(sp.atan(sp.sqrt(sp.Rational(1, 5)))) * 180 / float(sp.pi) - 24.0948) < 1e-4)
require_true("(3.6) Painleve's rod (k = 1/3): 4/3", 2 * sp.sqrt(sp.Rational(1, 3) * sp.Rational(4, 3)) == sp.Rational(4, 3))
require_true("(3.6) thin hoop (k = 1/2): sqrt(3) at 30 deg", 2 * sp.sqrt(sp.Rational(1, 2) * sp.Rational(3, 2)) == sp.sqrt(3))


# (3.5) for thick coins: mu_P(theta) = (I_X/M + Lambda^2) / (Lambda H) with the rim's Lambda, H (rim.md 1.4, 1.7)
# and the inertia of the solid the program simulates (rim_inertia.md: a cylinder whose outer edges are rounded
# with rho), integrated here directly over z-slices (disc of radius a, or a - rho + sqrt(rho^2 - (|z| - d)^2) on
# the fillets), not from the page's closed forms. The sharp cylinder's I_X/M = a^2/4 + h^2/12 (the value the page
# used to quote, 1.171 and 1.138 for the toy) is not the program's once the edge is rounded.
def solid_IX_over_M(a_, h_, rho_):
    d_ = h_ / 2 - rho_

    def radius(z):
        return a_ if abs(z) <= d_ else a_ - rho_ + mpmath.sqrt(max(rho_**2 - (abs(z) - d_) ** 2, 0))

    cuts = sorted({-h_ / 2, -d_, d_, h_ / 2})
    V = mpmath.quad(lambda z: radius(z) ** 2, cuts)
    Jr = mpmath.quad(lambda z: radius(z) ** 4 / 2, cuts)  # integral r^2 dV / pi
    Jz = mpmath.quad(lambda z: z * z * radius(z) ** 2, cuts)
    return (Jr / 2 + Jz) / V


def least_mu_P(a_, h_, rho_):
    """(min mu_P, its theta in degrees) by golden-section search over theta in (0.2, 1.3) rad."""
    numbers = {a: a_, h: h_, rho: rho_}
    kX = solid_IX_over_M(a_, h_, rho_)
    Lam_n, H_n = (sp.lambdify((S, C), expr.subs(numbers), "mpmath") for expr in (Lam, H))

    def mu_P(th):
        s_, c_ = mpmath.sin(th), mpmath.cos(th)
        return (kX + Lam_n(s_, c_) ** 2) / (Lam_n(s_, c_) * H_n(s_, c_))

    lo, hi, ratio = mpmath.mpf("0.2"), mpmath.mpf("1.3"), (mpmath.sqrt(5) - 1) / 2
    for _ in range(120):
        x1, x2 = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
        lo, hi = (lo, x2) if mu_P(x1) < mu_P(x2) else (x1, hi)
    return float(mu_P((lo + hi) / 2)), float(mpmath.degrees((lo + hi) / 2))


mpmath.mp.dps = 30
for name, dims, stated in (("the toy, rho = h/2", (0.0375, 0.013, 0.0065), (1.1225, 28.12)),
                           ("the toy, rho = 1.6 mm", (0.0375, 0.013, 0.0016), (1.1349, 32.94)),
                           ("1-euro-like, rho = h/2", (0.011625, 0.00233, 0.001165), (1.1122, 26.15))):
    value, angle = least_mu_P(*dims)
    require_true(f"(3.6) thick coin, {name}: min mu_P {value:.5f} at {angle:.2f} deg as stated",
                 abs(value - stated[0]) < 5e-5 and abs(angle - stated[1]) < 5e-3)
a_t, h_t, rho_t = 0.0375, 0.013, 0.0065
require_true("(3.6) the rounded toy's I_X / M is below the sharp cylinder's a^2/4 + h^2/12",
             solid_IX_over_M(a_t, h_t, rho_t) < a_t**2 / 4 + h_t**2 / 12)
print(f"       ({time.monotonic() - started:.1f} s)")

# ================================================================================ (d) §4
for sigma in (1, -1):
    A, B, c, c_comp, c_floor, H, Lam = geometry(sigma)
    # (4.4) Kinematics of rolling, for any omega': the vertical acceleration of G is d2H/dt2 and the material
    # contact point has no acceleration, so the rolling solution (omega'_r, R_r) satisfies the sliding system
    # with R = R_r, i.e. with mu s_hat = -F_r / N_r.
    d_r, R_r, a_G_sym, m_r = rolling_from_scratch(sigma)
    v_y = dth(H) * wX
    a_y = dth(v_y) * wX + sp.diff(v_y, wX) * dX
    require(f"(4.4) rolling: a_G . y = d2H/dt2 for every omega', sigma = {sigma}", a_G_sym.dot(yhat) - a_y)
    wdot_sym = dOmegaSym + Omega.cross(omega)
    require_all(f"(4.4) rolling: a_G + omega-dot x c + omega x c-dot = 0 for every omega', sigma = {sigma}",
                a_G_sym + wdot_sym.cross(c) + omega.cross(c_floor))
    # ... and Euler holds with R_r (rim.md 2.6): so the sliding Euler equation with R = R_r gives omega'_r.
    require_all(f"(4.4) rolling: I omega' + Omega x I omega = c x R_r + tau, sigma = {sigma}",
                inertia * d_r + Omega.cross(inertia * omega) - c.cross(R_r) - tau)
    # Condensed horizontal compliance: Schur complement of y.W.y, in the basis (e_X, h).
    W = delassus(c)
    Wyy = yhat.dot(W * yhat)
    basis = [eX, hh]
    Wc = sp.Matrix(2, 2, lambda i, j: basis[i].dot(W * basis[j]) - basis[i].dot(W * yhat) * yhat.dot(W * basis[j]) / Wyy)
    w1 = 1 / M + A**2 / IZ + B**2 / IX
    w2 = (IX + M * (A**2 + B**2)) / (M * (IX + M * Lam**2))
    require(f"(4.3) W_c is diagonal in (e_X, h), sigma = {sigma}", Wc[0, 1])
    require(f"(4.3) w_1 = 1/M + A^2/I_Z + B^2/I_X, sigma = {sigma}", Wc[0, 0] - w1)
    require(f"(4.3) w_2 = (I_X + M (A^2 + B^2)) / (M (I_X + M Lambda^2)), sigma = {sigma}", Wc[1, 1] - w2)
    nu_h = M * H * Lam / (IX + M * Lam**2)
    require(f"(4.3) nu = -P_h W y / (y . W y) has no e_X part, sigma = {sigma}", -eX.dot(W * yhat) / Wyy)
    require(f"(4.3) nu_h = M H Lambda / (I_X + M Lambda^2), sigma = {sigma}", -hh.dot(W * yhat) / Wyy - nu_h)
    # The held contact: N = N_r + nu . (F - F_r) for any horizontal F (R = N y + F, y.(W R + b) = 0).
    Fx_, Fh_, Nr_, Frx, Frh = sp.symbols("F_x F_h N_r0 F_rx F_rh")
    R_any = Nr_ * yhat + Frx * eX + Frh * hh
    b_any = -W * R_any                      # b of a state whose rolling reaction is R_any
    Fnew = Fx_ * eX + Fh_ * hh
    N_new = -(yhat.dot(b_any) + yhat.dot(W * Fnew)) / Wyy
    require(f"(4.2) N = N_r + nu . (F - F_r), sigma = {sigma}", N_new - (Nr_ + nu_h * (Fh_ - Frh)))

    # (4.5)-(4.6): at the cone's edge R_r = N_r (y + mu_s f_hat); b = -W R_r. Slide with mu_k, s_hat = -f_hat.
    Nr, mus, muk = sp.symbols("N_r mu_s mu_k", positive=True)
    R_roll = Nr * (yhat + mus * f_hat)
    b = -W * R_roll
    x_k = yhat + muk * f_hat
    N_k = -yhat.dot(b) / yhat.dot(W * x_k)
    sdot = W * (N_k * x_k) + b
    require(f"(4.5) the slip acceleration is horizontal, sigma = {sigma}", sdot.dot(yhat))
    require_all(f"(4.4) mu_k = mu_s: the slip acceleration is zero at the switch, sigma = {sigma}",
                sdot.subs(muk, mus))
    Dk = M * yhat.dot(W * x_k)   # D at (mu_k, s_hat = -f_hat)
    Wyy = 1 / M + Lam**2 / IX    # (3.4), checked
    Delta_f = (muk - mus) * Nr * M * Wyy / Dk
    Wc_f = w1 * cg * eX + w2 * sg * hh   # (4.3), checked
    require_all(f"(4.5) s-dot = Delta_f W_c f_hat, Delta_f = (mu_k - mu_s) N_r M (y.W.y) / D_k, sigma = {sigma}",
                sdot - Delta_f * Wc_f)
    require(f"(4.6) s-dot . s_hat = (mu_s - mu_k) N_r M (y.W.y) / D_k (f.W_c.f), sigma = {sigma}",
            sdot.dot(-f_hat) - (mus - muk) * Nr * M * Wyy / Dk * (w1 * cg**2 + w2 * sg**2))
    require(f"(4.5) D_k = M (y.W.y)(1 - mu_k nu . f_hat), sigma = {sigma}",
            Dk - M * Wyy * (1 - muk * nu_h * sg))
print(f"       ({time.monotonic() - started:.1f} s)")

# (4.7)-(4.8) mu_k = mu_s: first order in t after the switch. Abstract algebra in the horizontal plane with
# W_c = diag(w1, w2) in the orthonormal basis (e_X, h), nu = (0, nu_h), f_hat = (cg, sg), f_perp = (-sg, cg),
# the rolling demand F_r(t) = F_r + t Fdot, N_r(t) = N_r + t Ndot. Unknowns: lambda (s = -lambda t^2 / 2 f_hat
# + O(t^3)), d (friction direction -s_hat = f_hat - d t f_perp + O(t^2)), and Delta_1 = (F - F_r) / t.
w1s, w2s, nuh, Nr, mus, Fx, Fh, Ndot, lam_, d_ = sp.symbols("w1 w2 nu_h N_r mu Fdot_x Fdot_h Ndot lambda d")
Wc2 = sp.diag(w1s, w2s)
nu2 = sp.Matrix([0, nuh])
f2 = sp.Matrix([cg, sg])
fp2 = sp.Matrix([-sg, cg])
Fdot = sp.Matrix([Fx, Fh])
E = mus * Ndot * f2 - Fdot
D1 = sp.Matrix(sp.symbols("D1_x D1_h"))
# F - F_r = mu N (-s_hat) - F_r(t), N = N_r(t) + nu . (F - F_r) (the held contact), -s_hat = f_hat - d t f_perp:
# first order in t: Delta_1 = E - mu N_r d f_perp + mu (nu . Delta_1) f_hat; and W_c Delta_1 = -lambda f_hat.
eqs = list(D1 - (E - mus * Nr * d_ * fp2 + mus * nu2.dot(D1) * f2)) + list(Wc2 * D1 + lam_ * f2)
sol = sp.solve(eqs, list(D1) + [lam_, d_], dict=True)[0]
kappa = f2.dot(Fdot) - mus * Ndot                      # rate at which |F_r| - mu N_r grows
Wc2inv = Wc2.inv()
beta_ = (f2 - mus * nu2).dot(Wc2inv * f2)
require("(4.7) lambda = kappa / beta, beta = (f_hat - mu nu) . W_c^-1 f_hat", sol[lam_] - kappa / beta_)
require("(4.8) d = (-f_perp . Fdot + lambda f_perp . W_c^-1 f_hat) / (mu N_r)",
        sol[d_] - (-fp2.dot(Fdot) + sol[lam_] * fp2.dot(Wc2inv * f2)) / (mus * Nr))
require("(4.7) coin: beta = cg^2 / w1 + sg (sg - mu nu_h) / w2",
        beta_ - (cg**2 / w1s + sg * (sg - mus * nuh) / w2s))
# The statement after (4.8): thin disk, mu <= 1 keeps beta > 0 for every tilt and direction.
import math
worst = math.inf
for i in range(1, 90):
    th_ = math.radians(i)
    s_, c_ = math.sin(th_), math.cos(th_)
    kd = 0.25
    w1n = 1 + 1 / 0.5                                   # M = a = 1: 1/M + a^2/I_Z
    w2n = (kd + 1) / (kd + s_**2)
    nun = s_ * c_ / (kd + s_**2)
    for j in range(360):
        gam = math.radians(j)
        worst = min(worst, math.cos(gam)**2 / w1n + math.sin(gam) * (math.sin(gam) - 1.0 * nun) / w2n)
require_true(f"(4.7) thin disk, mu = 1: beta > 0 on every tilt and direction (min {worst:.4f} M)", worst > 0)
print(f"       ({time.monotonic() - started:.1f} s)")

# ================================================================================ (e) §5
t, v0 = sp.symbols("t v_0", positive=True)
for name, geo in (("thin", {h: 0, rho: 0}), ("fully rounded", {h: 2 * rho})):
    dOm, res = sliding_from_scratch(1)
    upright = {S: 0, C: 1, wX: 0, wY: 0, cb: 1, sb: 0, tX: 0, tY: 0, tZ: 0}
    res0 = sp.expand(res.subs(geo).subs(upright))
    N_up = normal_force(res0)
    dOm0 = sp.simplify(dOm.subs(geo).subs(upright).subs(N, N_up))
    require(f"(5.1) {name}: N = M g", N_up - M * g)
    require_all(f"(5.1) {name}: upright, slip along e_X: omega' = (0, 0, -mu M g a / I_Z)",
                dOm0 - sp.Matrix([0, 0, -mu * M * g * a / IZ]))
    # omega_Y = 0 so the frame does not turn (phi' = 0): U1' = F . e_X / M = -mu g, U2' = 0 ((1.8) above).
    A, B, c, *_ = geometry(1)
    slip_x = (U1 + omega.cross(c).dot(eX)).subs(geo).subs(upright)
    require(f"(5.1) {name}: slip = v + a omega_Z", slip_x - (U1 + a * wZ))
    # Integrate: v = v0 - mu g t, omega_Z = -mu M g a t / I_Z; slip zero at t*.
    v_t = v0 - mu * g * t
    wZ_t = -mu * M * g * a / IZ * t
    t_star = sp.solve(sp.Eq(v_t + a * wZ_t, 0), t)[0]
    require(f"(5.2) {name}: t* = v0 / (mu g (1 + M a^2 / I_Z))", t_star - v0 / (mu * g * (1 + M * a**2 / IZ)))
    v_after = v_t.subs(t, t_star)
    require(f"(5.3) {name}: v after = v0 M a^2 / (I_Z + M a^2)", v_after - v0 * M * a**2 / (IZ + M * a**2))
    work = sp.integrate(mu * M * g * (v_t + a * wZ_t), (t, 0, t_star))
    require(f"(5.4) {name}: friction work = M v0^2/2 - (M + I_Z/a^2) v_after^2 / 2",
            work - (M * v0**2 / 2 - (M + IZ / a**2) * v_after**2 / 2))
    require(f"(5.4) {name}: ... = M v0^2 I_Z / (2 (I_Z + M a^2))", work - M * v0**2 * IZ / (2 * (IZ + M * a**2)))
    disk = {IZ: M * a**2 / 2}
    require_true(f"(5.5) {name}: disk t* = v0 / (3 mu g), v after = 2 v0 / 3, work = M v0^2 / 6",
                 sp.simplify((t_star - v0 / (3 * mu * g)).subs(disk)) == 0
                 and sp.simplify((v_after - 2 * v0 / 3).subs(disk)) == 0
                 and sp.simplify((work - M * v0**2 / 6).subs(disk)) == 0)
    # Rolling afterwards, upright, omega = (0, 0, omega_Z): omega' = 0 and no friction needed (fits any cone).
    d_r, R_r, *_ = rolling_from_scratch(1)
    roll0 = {S: 0, C: 1, wX: 0, wY: 0, tX: 0, tY: 0, tZ: 0}
    require_all(f"(5.3) {name}: upright straight rolling needs omega' = 0", d_r.subs(geo).subs(roll0))
    require_all(f"(5.3) {name}: ... and R = M g y, F = 0", (R_r - M * g * yhat).subs(geo).subs(roll0))

print(f"       ({time.monotonic() - started:.1f} s)")
claims.finish()
