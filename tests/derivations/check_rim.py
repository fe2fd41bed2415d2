#!/usr/bin/env python3
# Independent on purpose: a test oracle (ctest sympy_*) re-deriving docs/rim.md in SymPy; it never calls coinroll.
"""Symbolic checks of docs/rim.md (run with Debian's python3-sympy).

For general M, a, h, rho, I_X, I_Z, g, on both sides sigma = sign(theta) = +-1:
  (a)  (1.3)-(1.5)  c is the lowest point of the rim: the lower torus lies above it by a sum of
                    non-negative terms; the upper torus, the cylindrical band and the faces lie higher;
  (b)  (2.7)-(2.10) the general Euler-angle form, its components, and seed (14)-(16) at h = rho = 0;
  (c)  (4.4)        dE/dt = tau . omega along the general form (omega' from the solved system), 0 for tau = 0;
  (d)  (3.1)-(3.4)  the material-frame form gives the XYZ form's omega' (frames turned by psi about e_Z);
  (e)  §5           steady circles, spin in place, straight rolling, and the linearisation's characteristic
                    polynomial lambda^2 (lambda^2 + K) with K of (5.8);
  (f)  (2.12)       a sphere (a = rho, h = 2 rho, I_X = I_Z = 2/5 M a^2) keeps a constant velocity;
       (4.3)        the normal force sees a couple only through its X component.
Exits non-zero if any identity fails (each failure is printed).
"""
import time

import sympy as sp

from sympy_checks import Claims, numerator_on_circles

M, a, h, rho, g, IX, IZ = sp.symbols("M a h rho g I_X I_Z", positive=True)
th = sp.symbols("theta", real=True)
wX, wY, wZ, lam = sp.symbols("omega_X omega_Y omega_Z lambda", real=True)
dX, dY, dZ = sp.symbols("domega_X domega_Y domega_Z", real=True)  # omega' symbols where a form is linear in them
tX, tY, tZ = sp.symbols("tau_X tau_Y tau_Z", real=True)
S, C = sp.symbols("S C")  # sin(theta), cos(theta) as plain symbols
sn, cs, tn = sp.sin(th), sp.cos(th), sp.tan(th)

started = time.monotonic()
claims = Claims("docs/rim.md")


def plain(expr):
    return sp.sympify(expr).subs({sp.tan(th): sp.sin(th) / sp.cos(th)}).subs({sp.sin(th): S, sp.cos(th): C})


def require(name, expr):
    """expr == 0 as a rational function of sin, cos, reduced modulo sin^2 + cos^2 = 1 (exact)."""
    claims.vanishes(name, numerator_on_circles(plain(expr), [(S, C)]))


def require_all(name, vector):
    for i, component in enumerate(vector):
        require(f"{name} [{i}]", component)


def require_true(name, condition):
    claims.holds(name, condition)


yhat = sp.Matrix([0, cs, -sn])                 # floor normal in XYZ
omega = sp.Matrix([wX, wY, wZ])
Omega = sp.Matrix([wX, wY, -wY * tn])          # the frame XYZ's own angular velocity
inertia = sp.diag(IX, IX, IZ)
tau = sp.Matrix([tX, tY, tZ])


def geometry(sigma):
    A = a - rho + rho * cs
    B = sigma * (h / 2 - rho) + rho * sn
    return A, B


def general_form(sigma, with_tau=False):
    """Mass matrix m and right-hand side f of (2.7): m omega' = f, XYZ components."""
    A, B = geometry(sigma)
    c = sp.Matrix([0, -A, B])
    c_dot = sp.diff(c, th) * wX                           # (2.3) component derivative
    v = -omega.cross(c)
    m = inertia + M * (c.dot(c) * sp.eye(3) - c * c.T)
    f = (-Omega.cross(inertia * omega) + M * c.cross(Omega.cross(v) - omega.cross(c_dot))
         + M * g * c.cross(yhat) + (tau if with_tau else sp.zeros(3, 1)))
    return m, f, c, c_dot, v


def solve_block(m, f):
    """omega' = m^-1 f using the block structure (2.8): m_XY = m_XZ = 0."""
    if m[0, 1] != 0 or m[0, 2] != 0:
        require("(2.8) the X row of the mass matrix is decoupled", m[0, 1]**2 + m[0, 2]**2)
    det = m[1, 1] * m[2, 2] - m[1, 2]**2
    return sp.Matrix([f[0] / m[0, 0],
                      (m[2, 2] * f[1] - m[1, 2] * f[2]) / det,
                      (m[1, 1] * f[2] - m[1, 2] * f[1]) / det])


# ---------------------------------------------------------------------------------------- (a)
u, v_ = sp.symbols("u v", real=True)  # torus angles: u round the axis, v round the tube
for sigma in (1, -1):
    e = h / 2 - rho
    A, B = geometry(sigma)
    height_G = A * cs + B * sn
    require(f"(1.4) height of G, sigma = {sigma}",
            height_G - ((a - rho) * cs + e * sigma * sn + rho))
    radial = sp.Matrix([sp.cos(u), sp.sin(u), 0])
    axial = sp.Matrix([0, 0, 1])
    torus = lambda side: ((a - rho) + rho * sp.cos(v_)) * radial + (side * e + rho * sp.sin(v_)) * axial
    # Height above the floor of a rim point = height of G + (point - G) . y_hat.
    lower = height_G + torus(sigma).dot(yhat)
    # (1.5): a sum of two non-negative terms (cos theta > 0, a - rho + rho cos v >= 0 on the outer half).
    require(f"(1.5) lower torus = (a - rho + rho cos v)(1 + sin u) cos th + rho (1 - cos(v - th)), sigma = {sigma}",
            sp.expand_trig(lower - ((a - rho + rho * sp.cos(v_)) * (1 + sp.sin(u)) * cs
                                    + rho * (1 - sp.cos(v_ - th)))))
    contact = (-(a - rho) * sp.Matrix([0, 1, 0]) + sigma * e * axial) - rho * yhat
    require_all(f"(1.3) c is the torus point u = -pi/2, v = theta, sigma = {sigma}",
                torus(sigma).subs({u: -sp.pi / 2, v_: th}) - contact)
    # Upper torus (the other face): higher by 2 e |sin theta| = 2 e sigma sin theta, minus the same
    # non-negative terms.
    upper = height_G + torus(-sigma).dot(yhat)
    require(f"(1.5) upper torus = lower + 2 e sigma sin th, sigma = {sigma}",
            sp.expand(upper - lower - 2 * e * sigma * sn))
    # Cylindrical band r = a, |Z| <= e (cornered rim): lowest at Z = sigma e, rho (1 - cos th) above c.
    zeta = sp.symbols("zeta", real=True)
    band = height_G + (a * radial + zeta * axial).dot(yhat)
    require(f"(1.5) band's lowest line = rho (1 - cos th) + (e - sigma zeta) |sin th| above c, sigma = {sigma}",
            sp.expand(band.subs(u, -sp.pi / 2) - (rho * (1 - cs) + (sigma * e - zeta) * sn)))
    # Face Z = sigma h/2, radius r <= a - rho: lowest at its rim, rho (1 - sigma sin th) above c.
    face = height_G + ((a - rho) * sp.Matrix([0, -1, 0]) + sigma * h / 2 * axial).dot(yhat)
    require(f"(1.5) face rim = rho (1 - |sin th|) above c, sigma = {sigma}",
            sp.expand(face - rho * (1 - sigma * sn)))

# ---------------------------------------------------------------------------------------- (b)
Ma2, Mga = M * a**2, M * g * a
seed = sp.Matrix([(-(IZ + Ma2) * wY * wZ - IX * wY**2 * tn + Mga * sn) / (IX + Ma2),   # (14)
                  wX * wY * tn + IZ / IX * wZ * wX,                                    # (15)
                  Ma2 * wX * wY / (IZ + Ma2)])                                         # (16)
for sigma in (1, -1):
    m, f, *_ = general_form(sigma)
    thin = {h: 0, rho: 0}
    require_all(f"(2.10) h = rho = 0 gives seed (14)-(16), sigma = {sigma}",
                solve_block(m.subs(thin), f.subs(thin)) - seed)

# The explicit components (2.9) of the right-hand side, both sides.
for sigma in (1, -1):
    m, f, *_ = general_form(sigma)
    A, B = geometry(sigma)
    L = A + B * tn
    V = A * wZ + B * wY
    Gx = wY * (a - rho + B * tn) + rho * sn * wZ
    Lam = A * sn - B * cs
    require(f"(2.9) f_X, sigma = {sigma}",
            f[0] - (-IZ * wY * wZ - IX * tn * wY**2 - M * L * V * wY + M * rho * Lam * wX**2 + M * g * Lam))
    require(f"(2.9) f_Y, sigma = {sigma}", f[1] - wX * (IX * tn * wY + IZ * wZ + M * B * Gx))
    require(f"(2.9) f_Z, sigma = {sigma}", f[2] - wX * M * A * Gx)
    require(f"(2.8) mass matrix, sigma = {sigma}",
            (m - sp.Matrix([[IX + M * (A**2 + B**2), 0, 0], [0, IX + M * B**2, M * A * B],
                            [0, M * A * B, IZ + M * A**2]])).norm()**2)

# ---------------------------------------------------------------------------------------- (c)
for sigma in (1, -1):
    m, f, c, c_dot, v = general_form(sigma, with_tau=True)
    A, B = geometry(sigma)
    energy = (M * v.dot(v) / 2 + (IX * (wX**2 + wY**2) + IZ * wZ**2) / 2 + M * g * (A * cs + B * sn))
    dOmega = solve_block(m, f)
    dE = sp.diff(energy, th) * wX + sum(sp.diff(energy, w) * dw for w, dw in zip(omega, dOmega))
    require(f"(4.4) dE/dt = tau . omega, sigma = {sigma}", dE - tau.dot(omega))
    require(f"(4.4) dE/dt = 0 without a couple, sigma = {sigma}", dE.subs({tX: 0, tY: 0, tZ: 0}))
print(f"       ({time.monotonic() - started:.1f} s)")

# ---------------------------------------------------------------------------------------- (4.3)
for sigma in (1, -1):
    m, f, c, c_dot, v = general_form(sigma, with_tau=True)
    A, B = geometry(sigma)
    dOmega = solve_block(m, f)
    accel = -(dOmega.cross(c) + omega.cross(c_dot)) + Omega.cross(v)     # (4.1)
    N = M * accel.dot(yhat) + M * g
    require(f"(4.3) N = M (g - (H - rho) omega_X^2 - Lambda omega_X'), sigma = {sigma}",
            N - M * (g - (A * cs + B * sn - rho) * wX**2 - (A * sn - B * cs) * dOmega[0]))
    require(f"(1.7) c x y_hat = (Lambda, 0, 0), sigma = {sigma}",
            (c.cross(yhat) - sp.Matrix([A * sn - B * cs, 0, 0])).norm()**2)
    require(f"(1.7) Lambda = (a - rho) sin th - sigma e cos th, sigma = {sigma}",
            A * sn - B * cs - ((a - rho) * sn - sigma * (h / 2 - rho) * cs))
    require(f"(4.3) dN/dtau_Y = dN/dtau_Z = 0, sigma = {sigma}", sp.diff(N, tY)**2 + sp.diff(N, tZ)**2)

# ---------------------------------------------------------------------------------------- (d)
ps = sp.symbols("psi", real=True)
SP, CP = sp.symbols("SP CP")


def require_psi(name, expr):
    claims.vanishes(name, numerator_on_circles(plain(expr).subs({sp.sin(ps): SP, sp.cos(ps): CP}), [(S, C), (SP, CP)]))


# Material components of an XYZ vector: b1 = cos psi e_X + sin psi e_Y, b2 = -sin psi e_X + cos psi e_Y.
bodyFromXYZ = sp.Matrix([[sp.cos(ps), sp.sin(ps), 0], [-sp.sin(ps), sp.cos(ps), 0], [0, 0, 1]])
psDot = wZ + tn * wY
for sigma in (1, -1):
    m, f, *_ = general_form(sigma, with_tau=True)
    w_b = bodyFromXYZ * omega
    u_b = bodyFromXYZ * yhat
    e_X, e_Y, e_Z = bodyFromXYZ[:, 0], bodyFromXYZ[:, 1], sp.Matrix([0, 0, 1])
    c_b = -(a - rho) * e_Y + sigma * (h / 2 - rho) * e_Z - rho * u_b                         # (3.1)
    c_dot_b = -(a - rho) * psDot * e_X + rho * w_b.cross(u_b)                                # (3.2)
    # The material derivative of c by the chain rule (theta, psi move; u = y_hat is fixed in the floor).
    chain = sp.diff(c_b, th) * wX + sp.diff(c_b, ps) * psDot
    for i in range(3):
        require_psi(f"(3.2) c' = -(a - rho) psi-dot e_X + rho omega x u, sigma = {sigma} [{i}]", (c_dot_b - chain)[i])
    m_b = inertia + M * (c_b.dot(c_b) * sp.eye(3) - c_b * c_b.T)
    b_b = (-w_b.cross(inertia * w_b) - M * c_b.cross(w_b.cross(c_dot_b) + w_b.cross(w_b.cross(c_b)))
           + M * g * c_b.cross(u_b) + bodyFromXYZ * tau)
    # omega_b' = T omega' + psi-dot T_psi omega. With m invertible, A_b omega_b' = b_b holds for the XYZ
    # form's omega' iff T^t A_b T = m and T^t (b_b - psi-dot A_b T_psi omega) = f.
    T = bodyFromXYZ
    for i, entry in enumerate(T.T * m_b * T - m):
        require_psi(f"(3.4) mass matrices agree, sigma = {sigma} [{i}]", entry)
    for i, entry in enumerate(T.T * (b_b - psDot * m_b * sp.diff(T, ps) * omega) - f):
        require_psi(f"(3.4) right-hand sides agree, sigma = {sigma} [{i}]", entry)
print(f"       ({time.monotonic() - started:.1f} s)")

# ---------------------------------------------------------------------------------------- (e)
for sigma in (1, -1):
    m, f, *_ = general_form(sigma)
    A, B = geometry(sigma)
    dOmega = solve_block(m, f)
    H = A * cs + B * sn
    L = H / cs
    Lam = A * sn - B * cs
    V = A * wZ + B * wY
    P = IX * tn + M * B * L                                                       # (5.2)
    Q = IZ + M * A * L
    steady_residual = P * wY**2 + Q * wZ * wY - M * g * Lam                       # (5.1)
    require(f"(5.1) omega_X = 0: omega_Y' = omega_Z' = 0, sigma = {sigma}",
            dOmega[1].subs(wX, 0)**2 + dOmega[2].subs(wX, 0)**2)
    require(f"(5.1) omega_X = 0: m_XX omega_X' = -(P w_Y^2 + Q w_Z w_Y - M g Lambda), sigma = {sigma}",
            (m[0, 0] * dOmega[0]).subs(wX, 0) + steady_residual)
    # Steady states parametrised by (theta, omega_Y): omega_Z from (5.1), linear in it.
    wZ_steady = (M * g * Lam - P * wY**2) / (Q * wY)
    # Linearisation (5.5)-(5.8).
    k = IX * tn * wY + IZ * wZ
    Gx = wY * (a - rho + B * tn) + rho * sn * wZ
    det = IX * IZ + M * (IX * A**2 + IZ * B**2)
    alpha = ((IZ + M * A**2) * k + M * IZ * B * Gx) / det                           # (5.6)
    beta = M * A * (IX * Gx - B * k) / det
    dfdth = (-IX * wY**2 / cs**2 - M * wY * (B * V / cs**2 + L * rho * (wY * cs - wZ * sn))
             + M * g * (H - rho))                                                 # (5.7)
    dfdwY = -IZ * wZ - 2 * IX * tn * wY - M * L * (A * wZ + 2 * B * wY)
    dfdwZ = -(IZ + M * A * L) * wY
    mXX = IX + M * (A**2 + B**2)
    K = -(dfdth + alpha * dfdwY + beta * dfdwZ) / mXX                              # (5.8)
    f_X = m[0, 0] * dOmega[0]
    require(f"(5.7) df_X/dtheta at omega_X = 0, sigma = {sigma}", sp.diff(f_X, th).subs(wX, 0) - dfdth)
    require(f"(5.7) df_X/domega_Y, sigma = {sigma}", sp.diff(f_X, wY).subs(wX, 0) - dfdwY)
    require(f"(5.7) df_X/domega_Z, sigma = {sigma}", sp.diff(f_X, wZ).subs(wX, 0) - dfdwZ)
    require(f"(5.5) df_X/domega_X = 0 at omega_X = 0 (mirror symmetry), sigma = {sigma}",
            sp.diff(f_X, wX).subs(wX, 0))
    require(f"(5.6) alpha = d omega_Y'/d omega_X, sigma = {sigma}", sp.diff(dOmega[1], wX).subs(wX, 0) - alpha)
    require(f"(5.6) beta = d omega_Z'/d omega_X, sigma = {sigma}", sp.diff(dOmega[2], wX).subs(wX, 0) - beta)
    # The Jacobian of (theta, omega_X, omega_Y, omega_Z)' at omega_X = 0 has the pattern
    #   [[0, 1, 0, 0], [j10, 0, j12, j13], [0, alpha, 0, 0], [0, beta, 0, 0]]
    # (f_Y, f_Z are proportional to omega_X, f_X is even in it), whose characteristic polynomial is
    # lambda^2 (lambda^2 - j10 - j12 alpha - j13 beta). Checked entry by entry, then K against (5.8)
    # on the steady states; cheaper than expanding the 4x4 determinant of the full rational entries.
    state = [th, wX, wY, wZ]
    rates = [wX, dOmega[0], dOmega[1], dOmega[2]]
    zero_entries = [(1, 1), (2, 0), (2, 2), (2, 3), (3, 0), (3, 2), (3, 3)]
    for row, col in zero_entries:
        require(f"(5.5) J[{row}][{col}] = 0 at omega_X = 0, sigma = {sigma}",
                sp.diff(rates[row], state[col]).subs(wX, 0))
    j10, j12, j13, j21, j31 = sp.symbols("j10 j12 j13 j21 j31")
    pattern = sp.Matrix([[0, 1, 0, 0], [j10, 0, j12, j13], [0, j21, 0, 0], [0, j31, 0, 0]])
    require(f"(5.5) the pattern's characteristic polynomial, sigma = {sigma}",
            (lam * sp.eye(4) - pattern).det() - lam**2 * (lam**2 - j10 - j12 * j21 - j13 * j31))
    # j_theta = (df_X/dtheta - f_X m_XX' / m_XX) / m_XX, j_Y, j_Z = (df_X/domega_{Y,Z}) / m_XX at omega_X = 0 with
    # (5.7)'s derivatives; so -(j_theta + j_Y alpha + j_Z beta) = K + f_X m_XX' / m_XX^2, and f_X = 0 on the
    # steady states, where omega_Z = wZ_steady makes (5.1) vanish. (Setting omega_X = 0 before
    # differentiating is exact and much faster; alpha and beta are common factors, already checked.)
    tilt_rate = dOmega[0].subs(wX, 0)
    require(f"(5.5) j_theta = ((5.7) + (5.1) m_XX' / m_XX) / m_XX, sigma = {sigma}",
            sp.diff(tilt_rate, th) - (dfdth + steady_residual * sp.diff(mXX, th) / mXX) / mXX)
    require(f"(5.5) j_Y = (5.7) / m_XX, sigma = {sigma}", sp.diff(tilt_rate, wY) - dfdwY / mXX)
    require(f"(5.5) j_Z = (5.7) / m_XX, sigma = {sigma}", sp.diff(tilt_rate, wZ) - dfdwZ / mXX)
    require(f"(5.1) omega_Z = (M g Lambda - P omega_Y^2) / (Q omega_Y) is steady, sigma = {sigma}",
            steady_residual.subs(wZ, wZ_steady))
    print(f"ok     (5.8) hence det(lambda I - J) = lambda^2 (lambda^2 + K) on every steady state, sigma = {sigma}")
    print(f"       ({time.monotonic() - started:.1f} s)")

    # Spin in place (5.3): omega parallel to c, so v = 0; omega_Y^2 from (5.1) with V = 0.
    wY2 = M * g * A * Lam / (IX * A * tn - IZ * B)
    on_spin = sp.expand(steady_residual.subs(wZ, -B * wY / A))
    require(f"(5.3) spin in place solves (5.1), sigma = {sigma}",
            on_spin.coeff(wY, 2) * wY2 + on_spin.coeff(wY, 0))
    require(f"(5.3) ... and (5.1) has no odd powers of omega_Y there, sigma = {sigma}", on_spin.coeff(wY, 1))
    _, _, c, _, v = general_form(sigma)
    require_all(f"(5.3) spin in place: v_G = 0, sigma = {sigma}", v.subs({wX: 0, wZ: -B * wY / A}))

    # Thin limit of K (3.6) and (5.2) -> seed 5.2 / (3.1).
    thin = {h: 0, rho: 0}
    alpha_thin = (IX * wY * tn + IZ * wZ) / IX
    beta_thin = Ma2 * wY / (IZ + Ma2)
    K_thin = ((IZ + Ma2) * (wZ * alpha_thin + wY * beta_thin) + 2 * IX * wY * tn * alpha_thin
              + IX * wY**2 / cs**2 - Mga * cs) / (IX + Ma2)
    require(f"(5.8) h = rho = 0 gives derivations (3.6), sigma = {sigma}", K.subs(thin) - K_thin)
    require(f"(5.1) h = rho = 0 gives derivations (3.1), sigma = {sigma}",
            steady_residual.subs(thin) - (IX * tn * wY**2 + (IZ + Ma2) * wZ * wY - Mga * sn))

    # (5.4) fully rounded rim (rho = h/2) rolling straight and upright: steady, K and the critical spin.
    rounded = {h: 2 * rho}
    require(f"(5.4) rho = h/2: theta = omega_Y = 0 is steady, sigma = {sigma}",
            steady_residual.subs(rounded).subs({wY: 0}).subs(th, 0))
    K_straight = ((IZ + Ma2) * IZ * wZ**2 / IX - M * g * (a - rho)) / (IX + Ma2)
    require(f"(5.9) rho = h/2: K of straight rolling, sigma = {sigma}",
            K.subs(rounded).subs(wY, 0).subs(th, 0) - K_straight)
    wc2 = M * g * (a - rho) * IX / (IZ * (IZ + Ma2))
    require(f"(5.9) K = 0 at the critical spin, sigma = {sigma}", K_straight.subs(wZ, sp.sqrt(wc2)))
    # A cornered rim (rho < h/2) is not steady upright: the residual there is -M g Lambda = M g sigma (h/2 - rho).
    require(f"(5.4) rho < h/2: upright residual is M g sigma (h/2 - rho), sigma = {sigma}",
            steady_residual.subs({wY: 0}).subs(th, 0) - M * g * sigma * (h / 2 - rho))

# (5.9) number for the toy (a = 37.5 mm, h = 13 mm, rho = h/2, I_X = M (a^2/4 + h^2/12), I_Z = M a^2/2).
toy = {a: sp.Rational(375, 10000), h: sp.Rational(13, 1000), g: sp.Rational(981, 100), M: 1}
toy_rho = toy[h] / 2
toy_wc = sp.sqrt((toy[g] * (toy[a] - toy_rho) * (toy[a]**2 / 4 + toy[h]**2 / 12)
                  / ((toy[a]**2 / 2) * (toy[a]**2 / 2 + toy[a]**2))))
thin_wc = sp.sqrt(toy[g] / (3 * toy[a]))
print(f"       toy critical spin {float(toy_wc):.6f} rad/s, thin coin sqrt(g/(3a)) {float(thin_wc):.6f} rad/s, "
      f"ratio {float(toy_wc / thin_wc):.6f}")

# ---------------------------------------------------------------------------------------- (f)
sphere = {a: rho, h: 2 * rho, IX: sp.Rational(2, 5) * M * rho**2, IZ: sp.Rational(2, 5) * M * rho**2}
for sigma in (1, -1):
    m, f, c, c_dot, v = general_form(sigma)
    m, f, c, c_dot, v = (x.subs(sphere) for x in (m, f, c, c_dot, v))
    require_all(f"(2.12) sphere: c = -rho y_hat, sigma = {sigma}", c + rho * yhat)
    dOmega = solve_block(m, f)
    accel = -(dOmega.cross(c) + omega.cross(c_dot)) + Omega.cross(v)
    require_all(f"(2.12) sphere: a_G = 0 for every omega and theta, sigma = {sigma}", accel)

print(f"       ({time.monotonic() - started:.1f} s)")
claims.finish()
