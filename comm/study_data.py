# The data of the study scene (comm/study.export), written for the aster
# project: a 2 x 1 plane-strain block pulled along x by an imposed
# displacement EPS * L on its right edge, free to contract along y
# (sigma_yy = 0), so that sigma_xx = E / (1 - NU^2) * EPS everywhere and
# the potential energy is 1/2 sigma_xx EPS per unit area. Both command
# files import it.
from code_aster.Commands import *

E = 200000.0
NU = 0.3
EPS = 1.0e-3
L = 2.0
H = 1.0


def energy(e, nu, eps, area):
    """Potential energy of the uniform plane-strain state over an area."""
    return 0.5 * e / (1.0 - nu * nu) * eps * eps * area


W_REF = energy(E, NU, EPS, L * H)
UX = FORMULE(VALE="EPS * X", NOM_PARA="X", EPS=EPS)
