#!/usr/bin/env python3
# Independent on purpose: a test oracle (ctest sympy_*) re-deriving docs/derivations.md in SymPy; it never calls coinroll.
"""Symbolic checks of docs/derivations.md (run with Debian's python3-sympy).

Checks, for general I_X, I_Z:
  (3.6)  the characteristic polynomial of the linearised tilt dynamics about a steady state with
         omega_X = 0 is lambda^2 (lambda^2 + K);
  (3.7)  straight rolling: K = -lambda^2 of seed 5.1, critical spin;
  (3.8)  spin in place: K in closed form;
  (2.1)  the coin-frame acceleration of the centre of mass.
Exits non-zero if any identity fails (each failure is printed).
"""

import sympy as sp

from sympy_checks import Claims, numerator_on_circles

M, a, g, IX, IZ = sp.symbols("M a g I_X I_Z", positive=True)
th, wX, wY, wZ, lam = sp.symbols("theta omega_X omega_Y omega_Z lambda")
Ma2, Mga = M * a**2, M * g * a

# Seed eqs. (14)-(17).
dwX = (-(IZ + Ma2) * wY * wZ - IX * wY**2 * sp.tan(th) + Mga * sp.sin(th)) / (IX + Ma2)
dwY = wX * wY * sp.tan(th) + IZ / IX * wZ * wX
dwZ = Ma2 * wX * wY / (IZ + Ma2)
dth = wX

f = sp.Matrix([dth, dwX, dwY, dwZ])
x = sp.Matrix([th, wX, wY, wZ])
J = f.jacobian(x).subs(wX, 0).subs({sp.tan(th): sp.sin(th) / sp.cos(th)})

alpha = (IX * wY * sp.tan(th) + IZ * wZ) / IX                                   # (3.3)
beta = Ma2 * wY / (IZ + Ma2)                                                    # (3.4)
K = ((IZ + Ma2) * (wZ * alpha + wY * beta) + 2 * IX * wY * sp.tan(th) * alpha
     + IX * wY**2 / sp.cos(th)**2 - Mga * sp.cos(th)) / (IX + Ma2)              # (3.6)


S, C, T = sp.symbols("S C T")  # sin(theta), cos(theta), tan(theta) as plain symbols


claims = Claims("docs/derivations.md")


def require(name, expr):
    # Trig functions become symbols tied by T = S / C and S^2 + C^2 = 1, so the check reduces to
    # rational-function algebra (fast, and exact).
    plain = sp.sympify(expr).subs({sp.tan(th): S / C, sp.sin(th): S, sp.cos(th): C})
    claims.vanishes(name, numerator_on_circles(plain, [(S, C)]))


charpoly = (lam * sp.eye(4) - J).det(method="berkowitz")
require("(3.6) det(lambda I - J) = lambda^2 (lambda^2 + K)", charpoly - lam**2 * (lam**2 + K))

lam2_seed = sp.Rational(4, 5) * (1 - 3 * wZ**2)
unit_disk = {M: 1, a: 1, g: 1, IX: sp.Rational(1, 4), IZ: sp.Rational(1, 2)}
require("(3.7) straight rolling, unit disk: -K = (4/5)(1 - 3 omega_Z^2)",
        (-K).subs({th: 0, wY: 0}).subs(unit_disk) - lam2_seed)
wc2 = Mga * IX / (IZ * (IZ + Ma2))
require("(3.7) K = 0 at the critical spin", K.subs({th: 0, wY: 0, wZ: sp.sqrt(wc2)}))

wY_spin = sp.sqrt(Mga * sp.cos(th) / IX)
K_spin = (Ma2 * wY_spin**2 + 3 * Mga * sp.sin(th)**2 / sp.cos(th)) / (IX + Ma2)
require("(3.8) spin in place", K.subs({wZ: 0}).subs(wY, wY_spin) - K_spin)

# (2.1): d v / d t in coin-frame components, v = a (-omega_Z, 0, omega_X), Omega = (omega_X, omega_Y, -omega_Y tan theta).
dwXs, dwZs = sp.symbols("dOmega_X dOmega_Z")
v = a * sp.Matrix([-wZ, 0, wX])
Omega = sp.Matrix([wX, wY, -wY * sp.tan(th)])
dv = a * sp.Matrix([-dwZs, 0, dwXs]) + Omega.cross(v)
expected = a * sp.Matrix([-(dwZs - wX * wY), -(wX**2 - wY * wZ * sp.tan(th)), dwXs + wY * wZ])
require("(2.1) centre-of-mass acceleration in the coin frame", (dv - expected).norm())
claims.finish()
