#!/usr/bin/env python3
# Independent on purpose: a test oracle (ctest sympy_*) re-deriving docs/quaternion_formulation.md in SymPy; it never calls coinroll.
"""Symbolic checks of docs/quaternion_formulation.md (run with Debian's python3-sympy).

With the attitude q = q_y(phi) q_x(theta) q_z(psi) and general I_X, I_Z, psi:
  (2.1)  e_y in material components is (cos th sin psi, cos th cos psi, -sin th), so the
         in-plane unit vector e_Y is (sin psi, cos psi, 0) and e_X = e_Y x e_Z;
  (2.4)  d/dt of c = -a e_Y in material components is -a psi-dot e_X, psi-dot from seed (19);
  (4.1)  q-dot from seed (17)-(19) by the chain rule equals q (0, omega_body) / 2;
  (3.4)  the solution of the 3x3 system equals seed (14)-(16) turned into the material frame.
Exits non-zero on the first failed identity.
"""
import sympy as sp
from sympy.algebras.quaternion import Quaternion

from sympy_checks import Claims, numerator_on_circles

M, a, g, IX, IZ = sp.symbols("M a g I_X I_Z", positive=True)
th, ph, ps = sp.symbols("theta phi psi", real=True)
wX, wY, wZ = sp.symbols("omega_X omega_Y omega_Z", real=True)
Ma2, Mga = M * a**2, M * g * a

S, C, SP, CP = sp.symbols("S C SP CP")  # sin/cos of theta and psi as plain symbols


claims = Claims("docs/quaternion_formulation.md")


def require(name, expr):
    """expr == 0 as a rational function of sin/cos, reduced modulo sin^2 + cos^2 = 1 (exact)."""
    plain = sp.sympify(expr).subs({sp.tan(th): sp.sin(th) / sp.cos(th)})
    plain = plain.subs({sp.sin(th): S, sp.cos(th): C, sp.sin(ps): SP, sp.cos(ps): CP})
    claims.vanishes(name, numerator_on_circles(plain, [(S, C), (SP, CP)]))


def require_all(name, vector):
    for i, component in enumerate(vector):
        require(f"{name} [{i}]", component)


def half_angle(angle, axis):
    return Quaternion(sp.cos(angle / 2), *[sp.sin(angle / 2) * n for n in axis])


def rotation_of(q):
    """floor-from-body rotation matrix of a unit quaternion, without sympy's normalising sqrt."""
    w, x, y, z = q.a, q.b, q.c, q.d
    return sp.Matrix([[1 - 2 * (y**2 + z**2), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                      [2 * (x * y + w * z), 1 - 2 * (x**2 + z**2), 2 * (y * z - w * x)],
                      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x**2 + y**2)]])


def trig_simplify(expr):
    # Half angles to full angles, so require() sees sin/cos of theta and psi only.
    return sp.expand_trig(sp.simplify(sp.expand(sp.expand_trig(expr))))


qy, qx, qz = half_angle(ph, (0, 1, 0)), half_angle(th, (1, 0, 0)), half_angle(ps, (0, 0, 1))
q = qy * qx * qz
R = rotation_of(q).applyfunc(trig_simplify)

# (2.1) e_y in material components and the seed's in-plane axes.
up = R.row(1).T
require_all("(2.1) e_y in material components", up - sp.Matrix([sp.cos(th) * sp.sin(ps), sp.cos(th) * sp.cos(ps), -sp.sin(th)]))
e_Y = sp.Matrix([sp.sin(ps), sp.cos(ps), 0])
e_X = e_Y.cross(sp.Matrix([0, 0, 1]))
require_all("(2.1) e_X = (cos psi, -sin psi, 0)", e_X - sp.Matrix([sp.cos(ps), -sp.sin(ps), 0]))

# Seed rates (17)-(19), (14)-(16) and the material-frame omega (1.3).
thDot, phDot, psDot = wX, wY / sp.cos(th), wZ + sp.tan(th) * wY
dwX = (-(IZ + Ma2) * wY * wZ - IX * wY**2 * sp.tan(th) + Mga * sp.sin(th)) / (IX + Ma2)
dwY = wX * wY * sp.tan(th) + IZ / IX * wZ * wX
dwZ = Ma2 * wX * wY / (IZ + Ma2)
w = sp.Matrix([sp.cos(ps) * wX + sp.sin(ps) * wY, -sp.sin(ps) * wX + sp.cos(ps) * wY, wZ])

# (2.4) c-dot: the in-plane unit vector turns at psi-dot; the formula of the code,
# -a (e_X . (e_y x omega) / cos theta) e_X, is that rate.
c = -a * e_Y
cDot_chain = sp.diff(c, ps) * psDot
require_all("(2.4) c-dot = -a psi-dot e_X", cDot_chain - (-a * psDot * e_X))
require("(2.4) psi-dot = e_X . (e_y x omega) / cos theta", e_X.dot(up.cross(w)) / sp.cos(th) - psDot)

# (4.1) kinematics.
qDot = [sp.diff(part, th) * thDot + sp.diff(part, ph) * phDot + sp.diff(part, ps) * psDot
        for part in (q.a, q.b, q.c, q.d)]
spin = q * Quaternion(0, *w)
require_all("(4.1) q-dot = q (0, omega) / 2", [trig_simplify(qDot[i] - spin_i / 2)
                                               for i, spin_i in enumerate((spin.a, spin.b, spin.c, spin.d))])

# (3.4) dynamics.
inertia = sp.diag(IX, IX, IZ)
A = inertia + M * (c.dot(c) * sp.eye(3) - c * c.T)
b = (-w.cross(inertia * w) - M * c.cross(w.cross(-a * psDot * e_X) + w.cross(w.cross(c)))
     + M * g * c.cross(up))
wDot = A.LUsolve(b)
# Seed (14)-(16) in the material frame: d/dt of R_z(-psi) omega_XYZ.
expected = sp.Matrix([sp.cos(ps) * dwX + sp.sin(ps) * dwY + psDot * w[1],
                      -sp.sin(ps) * dwX + sp.cos(ps) * dwY - psDot * w[0],
                      dwZ])
require_all("(3.4) angular acceleration = seed (14)-(16)", wDot - expected)
claims.finish()
