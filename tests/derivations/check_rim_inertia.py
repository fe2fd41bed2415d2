#!/usr/bin/env python3
# Independent on purpose: a test oracle (ctest sympy_*) re-deriving docs/rim_inertia.md in SymPy; it never calls coinroll.
"""Symbolic checks of docs/rim_inertia.md (run with Debian's python3-sympy).

The coin is a uniform solid of revolution whose (r, z) cross-section is the rectangle
[b, a] x [-h/2, h/2] with its two outer corners rounded by quarter circles of radius rho. Here the
volume, integral r^2 dV and integral z^2 dV are integrated directly over that section (weight
2 pi r, the fillet's arc as the z-limit), independently of the page's corner decomposition, and
compared with the closed forms (I.6)-(I.11) written exactly as src/physics/solid_inertia.cpp
evaluates them. Then the limits rho = 0 (I.12) and the sphere a = rho = h/2, b = 0 (I.13), and the
numbers of the page's toy-coin table. One line per claim, "ok ..." or "FAILED ..."; exits non-zero
if any claim failed.
"""
import sympy as sp

from sympy_checks import Claims

M, a, h = sp.symbols("M a h", positive=True)
b, rho, r = sp.symbols("b rho r", nonnegative=True)
pi = sp.pi
claims = Claims("docs/rim_inertia.md")


def claim(label, ok):
    claims.holds(label, ok)


def is_zero(expr):
    """expr (a rational function of the symbols and pi) vanishes identically."""
    return sp.expand(sp.numer(sp.together(sp.expand(expr)))) == 0


# ---- direct integration over the cross-section ---------------------------------------------
# For b <= r <= a - rho the section spans |z| <= h/2; for a - rho <= r <= a the arc bounds it,
# |z| <= (h/2 - rho) + sqrt(rho^2 - (r - (a - rho))^2). The z-integral is done first (even in z),
# then r; on the arc strip r = (a - rho) + rho sin(t), t in [0, pi/2], so the square root is
# rho cos(t) and SymPy integrates trigonometric polynomials instead of powers of a square root.
t = sp.symbols("t", real=True)


def direct(weight_in_r, z_power):
    """Integral of 2 pi r * weight_in_r(r) * z^z_power over the section."""
    c, d = a - rho, h / 2 - rho
    zint = lambda top: 2 * top ** (z_power + 1) / (z_power + 1)  # integral of z^k over [-top, top]
    flat = sp.integrate(sp.expand(2 * pi * r * weight_in_r(r) * zint(h / 2)), (r, b, c))
    r_arc = c + rho * sp.sin(t)
    dr = rho * sp.cos(t)
    integrand = 2 * pi * r_arc * weight_in_r(r_arc) * zint(d + rho * sp.cos(t)) * dr
    arc = sp.integrate(sp.expand(integrand), (t, 0, pi / 2))
    return sp.expand(flat + arc)


V_direct = direct(lambda s: 1, 0)
Jr_direct = direct(lambda s: s**2, 0)  # integral r^2 dV
Jz_direct = direct(lambda s: 1, 2)     # integral z^2 dV


# ---- the closed forms, as coded in src/physics/solid_inertia.cpp ----------------------------
def corner_terms(a, h, rho):
    """(I.6)-(I.8): one fillet's integrals of r, r^3, r z^2 over the area it removes."""
    c, d = a - rho, h / 2 - rho
    kappa = 1 - pi / 4
    cv = kappa * c * rho**2 + rho**3 / 6
    cr = kappa * c**3 * rho**2 + c**2 * rho**3 / 2 + (1 - 3 * pi / 16) * c * rho**4 + 7 * rho**5 / 60
    cz = (c * (kappa * d**2 * rho**2 + d * rho**3 / 3 + (sp.Rational(1, 3) - pi / 16) * rho**4)
          + d**2 * rho**3 / 6 + d * rho**4 / 4 + rho**5 / 10)
    return cv, cr, cz


def closed_form(M, a, b, h, rho):
    """(I.9)-(I.11): (V, integral r^2 dV, integral z^2 dV, I_X, I_Z)."""
    cv, cr, cz = corner_terms(a, h, rho)
    section = h * (a - b) * (a + b)
    V = pi * (section - 4 * cv)
    Jr = pi * (section * (a**2 + b**2) / 2 - 4 * cr)
    Jz = pi * (section * h**2 / 12 - 4 * cz)
    share = 4 / section
    volume_fraction = 1 - share * cv
    I_Z = M * ((a**2 + b**2) / 2 - share * cr) / volume_fraction
    I_X = M * ((a**2 + b**2) / 4 + h**2 / 12 - share * (cr / 2 + cz)) / volume_fraction
    return V, Jr, Jz, I_X, I_Z


# The corner decomposition itself: a rho x rho square minus a quarter disc. Its height above the arc
# at u = rho sin(t) from the arc's centre is rho - rho cos(t) (area and centroid).
height, du = rho - rho * sp.cos(t), rho * sp.cos(t)
fillet_area = sp.integrate(sp.expand(height * du), (t, 0, pi / 2))
fillet_moment = sp.integrate(sp.expand(rho * sp.sin(t) * height * du), (t, 0, pi / 2))
claim("(I.4)  fillet area (1 - pi/4) rho^2; centroid (10 - 3 pi) rho / (3 (4 - pi)) in from the corner",
      is_zero(fillet_area - (1 - pi / 4) * rho**2)
      and is_zero(rho - fillet_moment / fillet_area - (10 - 3 * pi) * rho / (3 * (4 - pi))))

V, Jr, Jz, I_X, I_Z = closed_form(M, a, b, h, rho)
claim("(I.9)  V = pi [h (a^2 - b^2) - 4 C_V] equals the direct integral of 2 pi r dA", is_zero(V - V_direct))
claim("(I.10) int r^2 dV = pi [h (a^4 - b^4)/2 - 4 C_r] equals the direct integral of 2 pi r^3 dA",
      is_zero(Jr - Jr_direct))
claim("(I.10) int z^2 dV = pi [h^3 (a^2 - b^2)/12 - 4 C_z] equals the direct integral of 2 pi r z^2 dA",
      is_zero(Jz - Jz_direct))
claim("(I.11) I_Z (normalised form as coded) = M int r^2 dV / V", is_zero(I_Z - M * Jr_direct / V_direct))
claim("(I.11) I_X (normalised form as coded) = M (int r^2 dV / 2 + int z^2 dV) / V",
      is_zero(I_X - M * (Jr_direct / 2 + Jz_direct) / V_direct))

# ---- limits ---------------------------------------------------------------------------------
I_X0, I_Z0 = (sp.simplify(e.subs(rho, 0)) for e in (I_X, I_Z))
claim("(I.12) rho = 0: I_X = M ((a^2 + b^2)/4 + h^2/12)", is_zero(I_X0 - M * ((a**2 + b**2) / 4 + h**2 / 12)))
claim("(I.12) rho = 0: I_Z = M (a^2 + b^2)/2", is_zero(I_Z0 - M * (a**2 + b**2) / 2))
claim("(I.12) rho = 0: V = pi h (a^2 - b^2)", is_zero(V.subs(rho, 0) - pi * h * (a**2 - b**2)))

sphere = {b: 0, h: 2 * a, rho: a}
claim("(I.13) a = rho = h/2, b = 0: V = 4/3 pi a^3", is_zero(V.subs(sphere) - sp.Rational(4, 3) * pi * a**3))
claim("(I.13) a = rho = h/2, b = 0: I_X = 2/5 M a^2", is_zero(I_X.subs(sphere) - sp.Rational(2, 5) * M * a**2))
claim("(I.13) a = rho = h/2, b = 0: I_Z = 2/5 M a^2", is_zero(I_Z.subs(sphere) - sp.Rational(2, 5) * M * a**2))

# Fully rounded rim rho = h/2: the rim is half a torus; Pappus gives its volume pi rho^2 / 2 * 2 pi
# (a - rho + 4 rho / (3 pi)), added to the cylinder of radius a - rho.
c_full = a - h / 2
pappus = pi * h * (c_full**2 - b**2) + pi * (h / 2) ** 2 / 2 * 2 * pi * (c_full + 4 * (h / 2) / (3 * pi))
claim("(I.14) rho = h/2: V = cylinder of radius a - h/2 + half torus (Pappus)", is_zero(V.subs(rho, h / 2) - pappus))

# ---- the page's toy-coin table ----------------------------------------------------------------
TABLE = {  # rho in m: (I_X, I_Z) in kg m^2 as printed in docs/rim_inertia.md, 4 significant digits
    0.0: (1.463e-4, 2.813e-4),
    0.0016: (1.456e-4, 2.800e-4),
    0.0065: (1.366e-4, 2.627e-4),
}
toy = {M: sp.Rational(4, 10), a: sp.Rational(375, 10000), b: 0, h: sp.Rational(13, 1000)}
thin_X, thin_Z = float((M * a**2 / 4).subs(toy)), float((M * a**2 / 2).subs(toy))
print(f"\ntoy coin M = 0.4 kg, a = 37.5 mm, h = 13 mm, b = 0; thin disk I_X = {thin_X:.6e}, I_Z = {thin_Z:.6e}")
for rho_value, (tab_X, tab_Z) in TABLE.items():
    val_X = float(I_X.subs(toy).subs(rho, sp.nsimplify(rho_value)))
    val_Z = float(I_Z.subs(toy).subs(rho, sp.nsimplify(rho_value)))
    print(f"  rho = {rho_value * 1e3:4.1f} mm: I_X = {val_X:.6e} ({val_X / thin_X - 1:+.4%} vs thin)"
          f"  I_Z = {val_Z:.6e} ({val_Z / thin_Z - 1:+.4%} vs thin)")
    claim(f"table rho = {rho_value * 1e3:.1f} mm matches to 4 digits",
          abs(val_X - tab_X) <= 5e-4 * tab_X and abs(val_Z - tab_Z) <= 5e-4 * tab_Z)

claims.finish()
