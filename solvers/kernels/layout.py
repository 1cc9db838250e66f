"""Layout of the flat parameter vector and the integer codes the compiled kernels dispatch on.

The kernels take only floats, arrays and ints (poliastro style); this module is the
contract between them and the Python layer that builds the vectors (`solvers.models.bodies`,
`solvers.models.cases`). Numba treats these module-level ints as compile-time constants.
"""

# --- parameter vector `p` (float64, length N_PARAMS) ---------------------------------
I1, I2, I3 = 0, 1, 2          # central principal moments of inertia
MASS = 3                      # m
CURV = 4                      # signed curvature k of the support (0: plane), CONVENTIONS.md
S1, S2, S3 = 5, 6, 7          # gyrostatic moment S (body axes)
GRAV = 8                      # g: gravity, U = m g (r(gamma), gamma)
BRUN = 9                      # eps: Brun field, U = eps/2 (I gamma, gamma)
# Support function of the body (its surface), h(gamma) =
#   sqrt(gamma.B gamma) + c |gamma| + d sqrt(g1^2 + g2^2) + (a, gamma)
# and r(gamma) = grad h (the support point in direction gamma), J = Hessian of h.
B11, B22, B33, B12, B13, B23 = 10, 11, 12, 13, 14, 15   # ellipsoid part, B symmetric PSD
BALL_C = 16                   # c: ball part (radius R of a ball, offset surface)
DISK_D = 17                   # d: sharp-edged disk part (radius R of a disk)
A1, A2, A3 = 18, 19, 20       # a: from the centre of mass to the geometric centre
FLAT_Z = 21                   # z: flat-base offset, r = (r1, r2, z)
# rubber: 1 adds the no-spin constraint (omega, gamma) = 0 to the full model, its reaction
# lambda gamma with lambda from d/dt (omega, gamma) = 0 (solvers/models/rubber_lagrange.py);
# 0 the marble model
RUBBER = 22
N_PARAMS = 23

# --- models: which state and which vector field ---------------------------------------
MODEL_TEST_OSC = 0            # y'' = -y in R^2 (integrator tests)
MODEL_TEST_KEPLER = 1         # planar Kepler problem in R^4 (integrator tests)
MODEL_FULL = 2                # state (M, gamma) in R^6, (1.1)-(1.3) (plane and sphere)
MODEL_FLAT = 3                # state (M, r1, r2) in R^5, (3.16)-(3.17) (flat base on a sphere)
MODEL_REV_REDUCED = 4         # state (gamma3, K1, K2, K3), (2.6) (body of revolution, plane)
# The animation's models: the state above plus the orientation Q (body axes -> space, 9
# entries row by row) and the centre of mass x_G, integrated along (solvers/models/kinematics.py:
# dQ/dt = Q [omega]x, dx_G/dt = Q (r x omega)). Only scenes that animate need them.
MODEL_FULL_SCENE = 5          # (M, gamma, Q, x_G) in R^18
MODEL_FLAT_SCENE = 6          # (M, r1, r2, Q, x_G) in R^17

STATE_DIM = (2, 4, 6, 5, 4, 18, 17)

EPS = 2.220446049250313e-16   # the unit round-off of float64 (the kernels' round-off tests)

# --- status codes returned by the right-hand side -------------------------------------
OK = 0
SING_INERTIA = 1              # I_Q singular
SING_FIT = 2                  # det(E - k J) <= 0: the body no longer fits the sphere
SING_EDGE = 3                 # disk flat: contact point undefined (sin theta = 0)
SING_NONFINITE = 4            # a non-finite value appeared
SING_REDUCED = 5              # reduced variables undefined (gamma3 = +-1)
STATUS_TEXT = (
    "ok",
    "tensor of inertia about the contact point is singular",
    "the body no longer fits the sphere (1 - k * radius of curvature reached 0)",
    "the disk lies flat (sin theta = 0): the contact point is undefined",
    "a non-finite value appeared in the state or its derivative",
    "the reduced variables are undefined at gamma3 = +-1 (axis vertical)",
)
