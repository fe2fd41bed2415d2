#!/usr/bin/env python3
# Independent on purpose: a test oracle (ctest sympy_*) re-deriving docs/euler_disk.md in SymPy; it never calls coinroll.
"""Symbolic checks of docs/euler_disk.md (run with Debian's python3-sympy).

Every numbered algebraic claim of the page is checked here, for general I_X, I_Z where the
page says so and for the thin disk (I_X = Ma^2/4, I_Z = Ma^2/2) in its section 3. One line per
claim, "ok     (2.3) ..." or "FAILED (2.3) ..."; exits non-zero if any claim failed. The last block
recomputes the toy numbers quoted in the page's table and fails if they drift.
"""
import math

import mpmath
import sympy as sp

from sympy_checks import Claims, numerator_on_circles

M, a, g, IX, IZ = sp.symbols("M a g I_X I_Z", positive=True)
mu, rho, delta, l, mus, rp, eps = sp.symbols("mu rho delta l mu_s r_p epsilon", positive=True)
Om, al, tau0, k, T = sp.symbols("Omega alpha t_0 k tau", positive=True)   # T = t0 - t > 0
th, ph = sp.symbols("theta phi", real=True)
wX, wY, wZ, dwX, dwY, dwZ = sp.symbols("omega_X omega_Y omega_Z dOmega_X dOmega_Y dOmega_Z",
                                       real=True)
tX, tY, tZ, t, p = sp.symbols("tau_X tau_Y tau_Z t p", real=True)
Ma2, Mga = M * a**2, M * g * a

S, C, SP, CP = sp.symbols("S C SP CP")  # sin/cos of theta and phi as plain symbols
claims = Claims("docs/euler_disk.md")


def reduce_trig(expr):
    """expr as a polynomial numerator in sin/cos of theta and phi, modulo sin^2 + cos^2 = 1."""
    plain = sp.sympify(expr).subs({sp.tan(th): sp.sin(th) / sp.cos(th)})
    plain = plain.subs({sp.sin(th): S, sp.cos(th): C, sp.sin(ph): SP, sp.cos(ph): CP})
    return numerator_on_circles(plain, [(S, C), (SP, CP)])


def is_zero(expr):
    expr = sp.sympify(expr)
    if expr.has(sp.sin(th), sp.cos(th), sp.tan(th), sp.sin(ph), sp.cos(ph)):
        return reduce_trig(expr) == 0
    if expr == 0:
        return True
    for simplify in (sp.cancel, sp.powsimp, sp.simplify):
        try:
            if sp.simplify(simplify(expr)) == 0:
                return True
        except (TypeError, NotImplementedError):  # pragma: no cover - defensive
            pass
    return False


def require(name, *exprs):
    """Every expression in exprs (scalars or matrices) vanishes identically."""
    residuals = []
    for expr in exprs:
        items = list(expr) if isinstance(expr, sp.MatrixBase) else [expr]
        residuals += [e for e in items if not is_zero(e)]
    claims.vanishes(name, residuals[0] if residuals else 0)


def require_true(name, condition, detail=""):
    claims.holds(name, condition, detail)


# ---------------------------------------------------------------------------------------------
# Section 1: effects as couples.
sth, cth, sph, cph = sp.sin(th), sp.cos(th), sp.sin(ph), sp.cos(ph)
eX_f = sp.Matrix([cph, 0, -sph])                      # rows of R(theta, phi), floor components
eY_f = sp.Matrix([sth * sph, cth, sth * cph])
eZ_f = sp.Matrix([cth * sph, -sth, cth * cph])
ey_f = sp.Matrix([0, 1, 0])
R = sp.Matrix.vstack(eX_f.T, eY_f.T, eZ_f.T)
require("(1.0) R(theta, phi) is a rotation: R R^t = 1, e_X x e_Y = e_Z",
        R * R.T - sp.eye(3), eX_f.cross(eY_f) - eZ_f)
ey = R * ey_f                                          # e_y in XYZ components
require("(1.0) e_y = (0, cos theta, -sin theta) in XYZ", ey - sp.Matrix([0, cth, -sth]))

IG = sp.diag(IX, IX, IZ)
c = sp.Matrix([0, -a, 0])                              # c = -a e_Y (XYZ)
A = IG + M * (a**2 * sp.eye(3) - c * c.T)
require("(1.4) A = I_G + M (a^2 1 - c c^t) = diag(I_X + Ma^2, I_X, I_Z + Ma^2)",
        A - sp.diag(IX + Ma2, IX, IZ + Ma2))

# Newton-Euler about G in the XYZ frame, which turns with Om_f = theta' e_X + phi' e_y.
w = sp.Matrix([wX, wY, wZ])
dw = sp.Matrix([dwX, dwY, dwZ])                        # time derivatives of the XYZ components
tau = sp.Matrix([tX, tY, tZ])
Om_f = sp.Matrix([wX, wY, -wY * sp.tan(th)])
v = -w.cross(c)                                        # no slip
dv = -dw.cross(c) + Om_f.cross(v)                      # c has constant XYZ components
Rforce = M * dv + M * g * ey                           # (1.2) first line
euler = IG * dw + Om_f.cross(IG * w) - c.cross(Rforce) - tau   # (1.2) second line
sol = sp.solve(list(euler), [dwX, dwY, dwZ], dict=True)[0]
seed = [(-(IZ + Ma2) * wY * wZ - IX * wY**2 * sp.tan(th) + Mga * sth),    # seed (14)-(16)
        (IX * wX * wY * sp.tan(th) + IZ * wZ * wX),
        (Ma2 * wX * wY)]
aug = [(seed[0] + tX) / (IX + Ma2), (seed[1] + tY) / IX, (seed[2] + tZ) / (IZ + Ma2)]
require("(1.5) Newton-Euler (1.2) solved for omega-dot = seed (14)-(16) + tau_i / A_ii",
        *[sol[d] - f for d, f in zip([dwX, dwY, dwZ], aug)])
require("(1.3) the coefficient matrix of omega-dot in (1.2) is A",
        sp.Matrix(euler).jacobian(dw) - A)

E = sp.Rational(1, 2) * Ma2 * (wX**2 + wZ**2) + sp.Rational(1, 2) * (
    IX * (wX**2 + wY**2) + IZ * wZ**2) + Mga * cth
dEdt = (sp.diff(E, th) * wX + sp.diff(E, wX) * aug[0] + sp.diff(E, wY) * aug[1]
        + sp.diff(E, wZ) * aug[2])
require("(1.6) dE/dt along (1.5) = tau . omega", dEdt - tau.dot(w))

N_formula = M * g - M * a * (sth * dwX + cth * wX**2)
tt = sp.symbols("t")
thf = sp.Function("theta")(tt)
height_acc = sp.diff(a * sp.cos(thf), tt, 2).subs(sp.Derivative(thf, (tt, 2)), dwX) \
    .subs(sp.Derivative(thf, tt), wX).subs(thf, th)
require("(1.7) e_y . dv/dt = d^2(a cos theta)/dt^2 = -a (sin theta dOmega_X + cos theta omega_X^2)",
        ey.dot(dv) - height_acc, height_acc + a * (sth * dwX + cth * wX**2))
require("(1.7) N = e_y . R = M g - M a (sin theta dOmega_X + cos theta omega_X^2)",
        ey.dot(Rforce) - N_formula)
N_tau = N_formula.subs(dwX, aug[0])
require("(1.8) N depends on the couple through tau_X only",
        sp.diff(N_tau, tY), sp.diff(N_tau, tZ))
h_f = eX_f.cross(ey_f)
h = R * h_f                                            # XYZ components
require("(1.8) h = e_X x e_y is unit, horizontal, h . e_X = 0, e_y . e_X = 0",
        h_f.dot(h_f) - 1, h_f[1], h_f.dot(eX_f), ey_f.dot(eX_f))

# ---------------------------------------------------------------------------------------------
# Section 2: the laws.
wn = w.dot(ey)
wh = w - wn * ey
require("(2.1) omega_h . e_y = 0, -(-C omega_h) . omega = C |omega_h|^2, omega_h . e_X = omega_X",
        wh.dot(ey), wh.dot(w) - wh.dot(wh), wh[0] - wX)

# Quasi-steady spin in place near flat: omega_X = omega_Z = 0, omega_Y = Omega cos(theta).
spin = {wX: 0, wZ: 0, wY: Om * cth}
require("(2.3) spin in place: |omega_h|^2 = Omega^2 sin^2 theta cos^2 theta (= Omega^2 alpha^2 + ...)",
        wh.dot(wh).subs(spin) - Om**2 * sth**2 * cth**2)
C_M = sp.pi * mu * a**3 / (4 * al**3)
P_M = C_M * (Om * al)**2
qs = {Om: sp.sqrt(4 * g / (a * al))}                   # Omega^2 alpha = 4 g / a
require("(2.3) P = C (Omega alpha)^2 = pi mu a^3 Omega^2 / (4 alpha) = pi mu g a^2 / alpha^2",
        P_M - sp.pi * mu * a**3 * Om**2 / (4 * al), P_M.subs(qs) - sp.pi * mu * g * a**2 / al**2)
alpha_M = (2 * sp.pi * mu * a / M * T) ** sp.Rational(1, 3)    # T = t0 - t, d/dt = -d/dT
require("(2.4) (3/2) M g a dalpha/dt = -pi mu g a^2/alpha^2 is solved by alpha^3 = (2 pi mu a/M)(t0-t)",
        -sp.Rational(3, 2) * Mga * sp.diff(alpha_M, T)
        + (sp.pi * mu * g * a**2 / al**2).subs(al, alpha_M))

# Lubrication: gap h0 = a alpha, wall velocity W = Omega alpha r cos(chi); p = (12 mu W0/h0^3) f(r) cos(chi).
r, chi = sp.symbols("r chi", positive=True)
f = sp.Function("f")
gen = sp.dsolve(f(r).diff(r, 2) + f(r).diff(r) / r - f(r) / r**2 - r, f(r)).rhs
C1, C2 = sp.symbols("C1 C2")
gen = gen.subs(C2, 0) if sp.limit(gen.subs(C1, 0).subs(C2, 1), r, 0) in (sp.oo, -sp.oo) else gen
gen = gen.subs(C1, 0) if sp.limit(gen.subs(C2, 0).subs(C1, 1), r, 0) in (sp.oo, -sp.oo) else gen
const = (gen.free_symbols & {C1, C2}).pop()
fsol = gen.subs(const, sp.solve(gen.subs(r, a), const)[0])
require_true("(2.5) f'' + f'/r - f/r^2 = r, f(a) = 0, f(0) finite: f = (r^3 - a^2 r)/8",
             sp.simplify(fsol - (r**3 - a**2 * r) / 8) == 0, f"got {fsol}")
h0 = a * al
pressure = 12 * mu * Om * al / h0**3 * fsol * sp.cos(chi)
wall = Om * al * r * sp.cos(chi)
P_lub = -sp.integrate(sp.integrate(pressure * wall * r, (chi, 0, 2 * sp.pi)), (r, 0, a))
require("(2.5) lubrication estimate P = pi mu a^3 Omega^2 / (8 alpha) = P_Moffatt / 2",
        P_lub - sp.pi * mu * a**3 * Om**2 / (8 * al), P_lub - P_M / 2)

# (2.5a) An annulus b <= r <= a (a ring's face; the hole open to the room, p = 0 on both edges). Any gap
# conductance K uniform over the face (Moffatt's h0^3 / (12 mu); the boundary layer's, h0 / delta_s times
# smaller, (2.6)) gives p = (W0 / K) f(r) cos(chi) with the same f, so the face's shape enters P only as
# the integral of f r^2, and P_annulus / P_disk is the same for both laws.
b, Kc = sp.symbols("b K", positive=True)
fann = sp.dsolve(f(r).diff(r, 2) + f(r).diff(r) / r - f(r) / r**2 - r, f(r)).rhs
unknowns = sorted(fann.free_symbols - {r}, key=str)
fann = fann.subs(sp.solve([fann.subs(r, a), fann.subs(r, b)], unknowns))
require_true("(2.5a) annulus: f = (r^3 - (a^2 + b^2) r + a^2 b^2 / r) / 8 solves (2.5) with f(a) = f(b) = 0",
             sp.simplify(fann - (r**3 - (a**2 + b**2) * r + a**2 * b**2 / r) / 8) == 0, f"got {fann}")
P_ann = -sp.integrate(sp.integrate(Om * al / Kc * fann * sp.cos(chi) * wall * r, (chi, 0, 2 * sp.pi)), (r, b, a))
P_disk_K = -sp.integrate(sp.integrate(Om * al / Kc * fsol * sp.cos(chi) * wall * r, (chi, 0, 2 * sp.pi)), (r, 0, a))
require("(2.5a) P_annulus = P_disk (1 - b^2/a^2)^3 for any uniform conductance K",
        sp.simplify(P_ann - P_disk_K * (1 - b**2 / a**2) ** 3))
require("(2.5a) b -> 0 gives the disk", sp.limit(P_ann, b, 0) - P_disk_K)
require("(2.5a) b -> a (a hoop) gives no face drag", sp.limit(P_ann, b, a))
require("(2.5a) K = h0^3 / (12 mu) gives back the disk's lubrication estimate at b = 0",
        P_disk_K.subs(Kc, h0**3 / (12 * mu)) - P_lub)

nu = mu / rho
dl = sp.sqrt(nu / Om)
P_BL = P_M * (a * al / dl)
require("(2.6) P_BL = P_Moffatt a alpha / delta = (pi/4) sqrt(mu rho) a^4 Omega^(5/2)",
        P_BL - sp.pi / 4 * sp.sqrt(mu * rho) * a**4 * Om**sp.Rational(5, 2))
require("(2.7) quasi-steady P_BL = sqrt(2) pi sqrt(mu rho) g^(5/4) a^(11/4) alpha^(-5/4)",
        P_BL.subs(qs) - sp.sqrt(2) * sp.pi * sp.sqrt(mu * rho) * g**sp.Rational(5, 4)
        * a**sp.Rational(11, 4) * al**sp.Rational(-5, 4))
alpha_BL = (nu / (2 * a**sp.Rational(3, 2) * sp.sqrt(g)))**sp.Rational(2, 3)
require("(2.8) P_BL = P_Moffatt where delta = a alpha; quasi-steady at alpha^(3/2) = nu/(2 a^(3/2) sqrt g)",
        (P_BL - P_M).subs(mu, rho * Om * a**2 * al**2),
        (dl - a * al).subs(qs).subs(al, alpha_BL))

psidot = wZ + sp.tan(th) * wY                          # seed (19)
require("(2.9) h = sin theta e_Y + cos theta e_Z, omega . h = psi-dot cos theta",
        h - sp.Matrix([0, sth, cth]), w.dot(h) - psidot * cth)
Nn, x = sp.symbols("N x", real=True)
Cp = sp.symbols("C_p", positive=True)                  # cos theta > 0 for |theta| < 90 deg
for sgn_name, xs in (("+", sp.Symbol("x", positive=True)), ("-", -sp.Symbol("x", positive=True))):
    # omega . h = psi-dot cos theta = xs * C_p, so psi-dot = xs.
    tau_roll_dot_w = -(delta * Nn / Cp) * sp.sign(xs * Cp) * (xs * Cp)
    require(f"(2.10) rolling resistance: -tau . omega = delta N |psi-dot| (psi-dot {sgn_name})",
            -tau_roll_dot_w - delta * Nn * sp.Abs(xs))
sr = sp.Symbol("s", real=True)
require("(2.10) tau_roll = -(delta N / cos theta) s h = -delta N s (0, tan theta, 1) in XYZ: the only couple "
        "with tau_X = 0 and tau . omega = -delta N s psi-dot",
        -(delta * Nn / cth) * sr * h - sp.Matrix([0, -delta * Nn * sr * sp.tan(th), -delta * Nn * sr]),
        (-(delta * Nn / cth) * sr * h).dot(w) + delta * Nn * sr * psidot)
require("(2.12) omega_n = omega . e_y = omega_Y cos theta - omega_Z sin theta; -tau . omega = l N omega_n sgn",
        wn - (wY * cth - wZ * sth), (l * Nn * sp.sign(x) * ey).dot(w) - l * Nn * sp.sign(x) * wn)
require("(2.13) uniform-pressure Coulomb patch: l = (2/3) mu_s r_p",
        sp.integrate(mus * (Nn / (sp.pi * rp**2)) * r * 2 * sp.pi * r, (r, 0, rp))
        - sp.Rational(2, 3) * mus * rp * Nn)
xp = sp.Symbol("x", positive=True)
require("(2.14) regularised sign: x sgn_eps(x) = x^2/sqrt(x^2+eps^2) (>= 0) -> |x| as eps -> 0",
        *[sp.limit(xs * xs / sp.sqrt(xs**2 + eps**2), eps, 0) - xp for xs in (xp, -xp)])

# ---------------------------------------------------------------------------------------------
# Section 3: near flat.
disk = {IX: Ma2 / 4, IZ: Ma2 / 2}
wY0 = sp.sqrt(Mga * cth / IX)
require("(3.1) spin in place is steady: (14)-(16) vanish at omega_X = omega_Z = 0, I_X omega_Y^2 = Mga cos theta",
        *[e.subs({wX: 0, wZ: 0}).subs(wY, wY0) for e in seed])
Om_disk = (wY0 / cth).subs(disk)                        # Omega = phi-dot = omega_Y / cos theta
require("(3.1) disk: Omega^2 sin(alpha) = Omega^2 cos(theta) = 4 g / a", Om_disk**2 * cth - 4 * g / a)
require("(3.2) E = (3/2) M g a cos theta = (3/2) M g a sin(alpha) (any I_X)",
        E.subs({wX: 0, wZ: 0}).subs(wY, wY0) - sp.Rational(3, 2) * Mga * cth)
require("(3.2) N = M g in the steady spin", N_formula.subs({wX: 0, dwX: 0}) - M * g)

q = sp.Symbol("q", positive=True)                     # q = 1 - p > 0, i.e. p < 1
p = 1 - q
Aamp = (2 * q * k / (3 * Mga))**(1 / q)
alpha_p = Aamp * T**(1 / q)                           # alpha^(1-p) = 2 (1-p) k T / (3 M g a)
ode_res = -sp.Rational(3, 2) * Mga * sp.diff(alpha_p, T) + k * alpha_p**p  # d/dt = -d/dT
require("(3.3) alpha^(1-p) = 2 (1-p) k (t0 - t) / (3 M g a) solves (3/2) M g a alpha' = -k alpha^p, p < 1",
        sp.simplify(sp.powsimp(sp.expand_power_base(ode_res / alpha_p, force=True), force=True)))
Om_p = sp.sqrt(4 * g / (a * alpha_p))
require("(3.4) Omega ~ (t0 - t)^(-1/(2(1-p)))",
        sp.simplify(sp.diff(sp.log(Om_p), T) * T + 1 / (2 * (1 - p))))


def law(name, P_qs, p_expect, gam_expect, omexp_expect, closed_lhs, closed_rhs):
    """P_qs(alpha) = k alpha^p; closed form closed_lhs(alpha) = closed_rhs * (t0 - t)."""
    pw = sp.simplify(al * sp.diff(sp.log(P_qs), al))
    kk = sp.simplify(P_qs / al**pw)
    gam = 1 / (1 - pw)
    require(f"{name} p = {p_expect}, alpha ~ (t0-t)^({gam_expect}), Omega ~ (t0-t)^({omexp_expect})",
            pw - p_expect, gam - gam_expect, -gam / 2 - omexp_expect)
    require(f"{name} closed form {closed_lhs} = ({closed_rhs}) (t0 - t), from (3.3)",
            closed_lhs - al**(1 - pw), sp.simplify(closed_rhs - 2 * (1 - pw) * kk / (3 * Mga)))
    return kk, pw


P_roll = delta * M * g * sp.sqrt(4 * g / (a * al))
k_M, _ = law("(3.5) Moffatt:", sp.pi * mu * g * a**2 / al**2, -2, sp.Rational(1, 3),
             -sp.Rational(1, 6), al**3, 2 * sp.pi * mu * a / M)
k_BL, _ = law("(3.6) boundary layer:", P_BL.subs(qs), -sp.Rational(5, 4), sp.Rational(4, 9),
              -sp.Rational(2, 9), al**sp.Rational(9, 4),
              3 * sp.pi / sp.sqrt(2) * sp.sqrt(mu * rho) * g**sp.Rational(1, 4)
              * a**sp.Rational(7, 4) / M)
k_R, _ = law("(3.7) rolling resistance:", P_roll, -sp.Rational(1, 2), sp.Rational(2, 3),
             -sp.Rational(1, 3), al**sp.Rational(3, 2), 2 * delta * sp.sqrt(g) / a**sp.Rational(3, 2))

require("(3.8) spin in place: |omega_n| = Omega cos^2(theta) = Omega sin^2(alpha)",
        wn.subs(spin) - Om * cth**2)
P_spin = l * M * g * sp.sqrt(4 * g / (a * al)) * al**2
require("(3.8) P_spin = l M g Omega alpha^2 = 2 l M g^(3/2) a^(-1/2) alpha^(3/2)  (p = 3/2)",
        P_spin - 2 * l * M * g**sp.Rational(3, 2) / sp.sqrt(a) * al**sp.Rational(3, 2))
t1, alpha0 = sp.symbols("t_1 alpha_0", positive=True)
alpha_spin = (alpha0**sp.Rational(-1, 2) + 2 * l * sp.sqrt(g) / (3 * a**sp.Rational(3, 2)) * t1)**-2
require("(3.9) alpha^(-1/2) = alpha_0^(-1/2) + (2 l sqrt g / (3 a^(3/2))) t solves (3/2) M g a alpha' = -P_spin",
        sp.simplify(sp.Rational(3, 2) * Mga * sp.diff(alpha_spin, t1) + P_spin.subs(al, alpha_spin)))
sgn = sp.Symbol("s", real=True)
tau_spin = -l * Nn * sgn * ey
d_wn = sp.Matrix([0, tau_spin[1] / IX, tau_spin[2] / (IZ + Ma2)]).dot(ey)
require("(3.10) the pivot couple's part of d(omega_n)/dt = -l N s (cos^2/I_X + sin^2/(I_Z + Ma^2))",
        d_wn + l * Nn * sgn * (cth**2 / IX + sth**2 / (IZ + Ma2)), tau_spin[0])

P_air = sp.pi * mu * g * a**2 / al**2
alpha_x = (sp.pi * mu * a**sp.Rational(5, 2) / (2 * delta * M * sp.sqrt(g)))**sp.Rational(2, 3)
require("(3.11) P_roll = P_air at alpha_x^(3/2) = pi mu a^(5/2) / (2 delta M sqrt g)",
        sp.simplify((P_roll - P_air).subs(al, alpha_x)))
alpha_xBL = (sp.sqrt(2) * sp.pi * sp.sqrt(mu * rho) * a**sp.Rational(13, 4)
             / (2 * delta * M * g**sp.Rational(1, 4)))**sp.Rational(4, 3)
require("(3.11) P_roll = P_BL at alpha^(3/4) = sqrt(2) pi sqrt(mu rho) a^(13/4) / (2 delta M g^(1/4))",
        sp.simplify((P_roll - P_BL.subs(qs)).subs(al, alpha_xBL)))
Ar = 2 * delta * M * g**sp.Rational(3, 2) / sp.sqrt(a)   # P_roll = Ar alpha^(-1/2)
Ba = sp.pi * mu * g * a**2                              # P_air  = Ba alpha^(-2)
xx = (al / alpha_x)**sp.Rational(3, 2)
tau_both = Mga * Ba / Ar**2 * (xx - sp.log(1 + xx))
require("(3.12) t0 - t = (M g a B/A^2)(x - ln(1 + x)), x = (alpha/alpha_x)^(3/2): d/dalpha matches",
        sp.simplify(sp.diff(tau_both, al) - sp.Rational(3, 2) * Mga / (P_roll + P_air)),
        Ar * alpha_x**sp.Rational(3, 2) / Ba - 1)
require("(3.12) ... and vanishes at alpha = 0; M g a B / A^2 = pi mu a^4 / (4 delta^2 M g)",
        sp.limit(tau_both, al, 0), Mga * Ba / Ar**2 - sp.pi * mu * a**4 / (4 * delta**2 * M * g))
require("(3.12) limits: alpha << alpha_x gives Moffatt's alpha^3 law, alpha >> alpha_x the rolling law",
        sp.limit(tau_both / al**3, al, 0) - M / (2 * sp.pi * mu * a),
        sp.limit(tau_both / al**sp.Rational(3, 2), al, sp.oo) - a**sp.Rational(3, 2) / (2 * delta * sp.sqrt(g)))
require("(3.13) crossover time t0 - t_x = (pi mu a^4 / (4 delta^2 M g)) (1 - ln 2)",
        sp.simplify(tau_both.subs(al, alpha_x)
                    - sp.pi * mu * a**4 / (4 * delta**2 * M * g) * (1 - sp.log(2))))

# ---------------------------------------------------------------------------------------------
# Section 4: t0 from the motion.
require("(4.1)-(4.2) quasi-steady alpha ~ (t0 - t)^n, n = 1/(1 - p): d ln alpha / d ln(t0 - t) = 1/q",
        sp.simplify(T * sp.diff(sp.log(alpha_p), T) - 1 / q))
gam, Kc = sp.symbols("gamma K", nonzero=True)
Et = Kc * (tau0 - t)**gam
u = Et / (-sp.diff(Et, t))
require("(4.3) the energy fit's u = E / P = (t0 - t)/gamma for E = K (t0 - t)^gamma", sp.simplify(u - (tau0 - t) / gam))
u_qs = (sp.Rational(3, 2) * Mga * al**q / k).subs(al, alpha_p)
require("(4.3) thin coin, E = (3/2) M g a alpha: u = (1 - p)(t0 - t), gamma = n",
        sp.simplify(sp.powsimp(sp.expand_power_base(u_qs - q * T, force=True), force=True)))
hh, rr = sp.symbols("h rho_r", positive=True)   # thickness, rim radius (rim.md 1.4 with theta -> pi/2 - alpha)
H_rim = (a - rr) * sp.sin(al) + (hh / 2 - rr) * sp.cos(al) + rr
require("(4.3) thick coin: H -> h/2 at alpha = 0, H - h/2 = (a - rho) alpha + O(alpha^2)",
        H_rim.subs(al, 0) - hh / 2, sp.diff(H_rim, al).subs(al, 0) - (a - rr))

# ---------------------------------------------------------------------------------------------
# Toy numbers quoted in the page (section 3 table).
toy = {a: 0.0375, M: 0.4, g: 9.81, mu: 1.8e-5, rho: 1.2, delta: 3.75e-6}
a0 = math.radians(10)
values = {
    "alpha_x [deg]": math.degrees(float(alpha_x.subs(toy))),
    "alpha_x (rolling = boundary layer) [deg]": math.degrees(float(alpha_xBL.subs(toy))),
    "alpha_BL [deg]": math.degrees(float(alpha_BL.subs(toy))),
    "t0 Moffatt [s]": float((al**3 / (2 * sp.pi * mu * a / M)).subs(toy).subs(al, a0)),
    "t0 boundary layer [s]": float((al**sp.Rational(9, 4) / (3 * sp.pi / sp.sqrt(2) * sp.sqrt(mu * rho)
                                   * g**sp.Rational(1, 4) * a**sp.Rational(7, 4) / M)).subs(toy).subs(al, a0)),
    "t0 rolling resistance [s]": float((al**sp.Rational(3, 2) / (2 * delta * sp.sqrt(g) / a**sp.Rational(3, 2)))
                                       .subs(toy).subs(al, a0)),
    "t0 rolling + Moffatt [s]": float(tau_both.subs(toy).subs(al, a0)),
    "t0 - t_x rolling + Moffatt [s]": float((sp.pi * mu * a**4 / (4 * delta**2 * M * g)
                                             * (1 - sp.log(2))).subs(toy)),
}
P_both_BL = sp.lambdify(al, (P_roll + P_BL.subs(qs)).subs(toy))
values["t0 rolling + boundary layer [s] (quadrature)"] = float(mpmath.quad(
    lambda s_: 1.5 * 0.4 * 9.81 * 0.0375 / P_both_BL(s_), [0, a0]))
quoted = {"alpha_x [deg]": 0.796, "alpha_BL [deg]": 0.273, "t0 Moffatt [s]": 501,
          "t0 boundary layer [s]": 45.0, "t0 rolling resistance [s]": 22.5,
          "t0 rolling + Moffatt [s]": 20.6, "t0 - t_x rolling + Moffatt [s]": 0.1555,
          "t0 rolling + boundary layer [s] (quadrature)": 14.44,
          "alpha_x (rolling = boundary layer) [deg]": 2.32}
for name, value in values.items():
    require_true(f"(3.14) toy {name} = {value:.4g} (page: {quoted[name]})",
                 abs(value / quoted[name] - 1) < 2e-3, f"computed {value}")


# (2.11c) The rolling-resistance couple's lever delta / sin(alpha) against the Hertz patch's half-length along
# the rim, for the example (0.449 kg, rim rho = 1.6 mm, face a - rho = 35.9 mm, delta = 3.75 um) of chromed
# steel (E 200 GPa, nu 0.3) on glass (70 GPa, 0.22). Curvature radii at the contact: rho across the rim,
# A / sin(alpha) along it (the torus' outer circle, normal curvature cos(theta) / A, rim.md 1.1). Hertz's
# elliptic contact (Johnson, Contact Mechanics §4.2): e^2 = 1 - (b/a)^2 solves
# R_x / R_y = (E(e) / (1 - e^2) - K(e)) / (K(e) - E(e)), and a^3 = 3 N R_x (K - E) / (pi E* e^2).
def hertz_half_axes(load, r_x, r_y, e_star):
    def ratio(m):
        return (mpmath.ellipe(m) / (1 - m) - mpmath.ellipk(m)) / (mpmath.ellipk(m) - mpmath.ellipe(m))
    lo, hi = mpmath.mpf(-60), mpmath.mpf(-1e-12)  # x = ln(1 - e^2); the ratio falls as x grows: bisect
    for _ in range(200):
        lo, hi = ((lo + hi) / 2, hi) if ratio(1 - mpmath.exp((lo + hi) / 2)) > r_x / r_y else (lo, (lo + hi) / 2)
    m = 1 - mpmath.exp((lo + hi) / 2)
    major = (3 * load * r_x * (mpmath.ellipk(m) - mpmath.ellipe(m)) / (mpmath.pi * e_star * m)) ** (mpmath.mpf(1) / 3)
    return float(major), float(major * mpmath.sqrt(1 - m))


E_star = 1 / ((1 - 0.3**2) / 200e9 + (1 - 0.22**2) / 70e9)
N_toy, rim_rho, face, delta_toy = 0.449 * 9.81, 1.6e-3, 0.0375 - 1.6e-3, 3.75e-6
near_circle = hertz_half_axes(N_toy, rim_rho * 1.0001, rim_rho, E_star)[0]
require_true("(2.11c) the elliptic solution tends to the circle's (3 N R / (4 E*))^(1/3) as R_x -> R_y",
             abs(near_circle / (3 * N_toy * rim_rho / (4 * E_star)) ** (1 / 3) - 1) < 1e-4, f"got {near_circle}")


def lever_over_patch(alpha_deg):
    alpha = math.radians(alpha_deg)
    return delta_toy / math.sin(alpha) / hertz_half_axes(N_toy, (face + rim_rho * math.sin(alpha))
                                                         / math.sin(alpha), rim_rho, E_star)[0]


low, high = 0.05, 0.5  # the lever exceeds the patch at the landing's 0.05 deg and not at 0.5: bisect
for _ in range(60):
    low, high = (low, (low + high) / 2) if lever_over_patch((low + high) / 2) < 1 else ((low + high) / 2, high)
crossing = (low + high) / 2
page = {"E* [GPa]": (E_star / 1e9, 55.1), "lever / patch at 2.8 deg": (lever_over_patch(2.8), 0.125),
        "lever / patch at 0.5 deg": (lever_over_patch(0.5), 0.367),
        "lever / patch at 0.05 deg": (lever_over_patch(0.05), 1.58), "crossing [deg]": (crossing, 0.1026),
        "patch half-length at 0.05 deg [mm]": (hertz_half_axes(N_toy, (face + rim_rho * math.sin(math.radians(0.05)))
                                                               / math.sin(math.radians(0.05)), rim_rho, E_star)[0]
                                              * 1e3, 2.72)}
for name, (value, quoted_value) in page.items():
    require_true(f"(2.11c) toy {name} = {value:.4g} (page: {quoted_value})",
                 abs(value / quoted_value - 1) < 5e-3, f"computed {value}")

claims.finish()
