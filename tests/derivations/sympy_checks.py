"""What the SymPy checks of docs/ share (each check_*.py verifies one page's boxed results).

A claim is an expression that must vanish identically, or a condition that must hold. Each is
printed as `ok     NAME` or `FAILED NAME: ...`; finish() prints the count and exits 1 if any failed,
so ctest sees every failing claim of a run, not only the first.
"""

import sys

import sympy as sp


def numerator_on_circles(expr, circles):
    """The numerator of expr as one fraction, reduced modulo s^2 + c^2 - 1 for each (s, c) pair.

    With sin and cos of each angle replaced by the symbols s, c beforehand, the expression is a
    rational function, and it vanishes identically exactly when this polynomial is 0 (exact).
    """
    numerator = sp.expand(sp.numer(sp.cancel(sp.together(sp.sympify(expr)))))
    for s, c in circles:
        if numerator.has(s):
            numerator = sp.expand(sp.rem(numerator, s**2 + c**2 - 1, s))
    return numerator


class Claims:
    def __init__(self, title):
        self.title = title
        self.failures = []

    def vanishes(self, name, residual):
        """The claim `name` holds when `residual` (already reduced) is 0."""
        if residual == 0:
            print(f"ok     {name}")
        else:
            self.failures.append(name)
            print(f"FAILED {name}: residual {residual}")

    def holds(self, name, condition, detail=""):
        if condition:
            print(f"ok     {name}")
        else:
            self.failures.append(name)
            print(f"FAILED {name} {detail}".rstrip())

    def finish(self):
        if self.failures:
            print(f"\n{len(self.failures)} claim(s) of {self.title} FAILED: {', '.join(self.failures)}")
            sys.exit(1)
        print(f"\nall claims of {self.title} hold")
        sys.exit(0)
