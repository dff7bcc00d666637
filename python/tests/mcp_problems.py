"""Small nonlinear MCPs with solutions known in closed form, shared by the MCP tests."""

import numpy as np

# The real root of r^3 + r - 1 = 0 by Cardano's formula (one real root since the discriminant is positive).
_D = np.sqrt(0.25 + 1.0 / 27.0)
ROOT = np.cbrt(0.5 + _D) + np.cbrt(0.5 - _D)


def cardano_F(z):
    # Row 1 free (F_1 = 0): z1^3 + z1 - 1 = 0 -> z1 = ROOT. Row 2 with l = 0: F_2 = z2^3 + z1 + 1 > 0 at z2 = 0
    # (z1 = ROOT > 0), so z2 = 0 and F_2 = ROOT + 1. Row 3 in [-1, 1]: F_3 = z3 - 2 z1 vanishes at z3 = 2 ROOT
    # = 1.36 > 1, so z3 = u = 1 with F_3 = 1 - 2 ROOT < 0 (the upper-bound sign).
    return np.array([z[0] ** 3 + z[0] - 1.0, z[1] ** 3 + z[0] + 1.0, z[2] - 2.0 * z[0]])


def cardano_J(z):
    return np.array([[3.0 * z[0] ** 2 + 1.0, 0.0, 0.0], [1.0, 3.0 * z[1] ** 2, 0.0], [-2.0, 0.0, 1.0]])


CARDANO_L = np.array([-np.inf, 0.0, -1.0])
CARDANO_U = np.array([np.inf, np.inf, 1.0])
CARDANO_SOLUTION = np.array([ROOT, 0.0, 1.0])

# Planted on the box [-1, 1]^3: F(z) = A z + z^3 + b with A symmetric positive definite, so F is strongly monotone
# (A's smallest eigenvalue plus the monotone cubic) and the solution is unique. z* = (1/4, 1, -1): row 1 interior
# needs F_1 = 0, row 2 at u needs F_2 <= 0 (take -1.5), row 3 at l needs F_3 >= 0 (take 0.75). A z* + z*^3 =
# (2 + 1/64, 3.25, -2), so b = (0, -1.5, 0.75) - (2.015625, 3.25, -2); every number is exact in binary.
PLANTED_A = np.array([[4.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 2.0]])
PLANTED_B = np.array([-2.015625, -4.75, 2.75])
PLANTED_L = -np.ones(3)
PLANTED_U = np.ones(3)
PLANTED_SOLUTION = np.array([0.25, 1.0, -1.0])


def planted_F(z):
    return PLANTED_A @ z + z ** 3 + PLANTED_B


def planted_J(z):
    return PLANTED_A + np.diag(3.0 * z ** 2)


def mcp_backends():
    """The registered backends that solve nonlinear MCPs, as the registry says (smcbench.solvers())."""
    import smcbench

    return [b["name"] for b in smcbench.solvers() if b["mcp"]]
