"""The EHL point contact the EHL and mixed-lubrication property tests solve (a 20 N contact of R = 10 mm on 16-32
cell grids) and their draws of valid and bad inputs."""
from __future__ import annotations

from hypothesis import strategies as st

from ballbench.lowmodel.contact import halfspace as hs
from ballbench.lowmodel.contact import hertz
from tests.property_support import positive, real

RX = 0.01  # R_x = R_y [m]


def ehl_case_rx(n: int):
    """``(E*, grid, gap)`` of the 20 N steel point contact on ``n x n`` cells over 5.5 x 5 Hertz semi-axes."""
    geometry = hertz.from_curvatures((1 / RX, 1 / RX), (0.0, 0.0), youngs_modulus=2.1e11, poisson_ratio=0.3)
    a = float(hertz.solve_load(geometry, 20.0).a)
    grid = hs.SurfaceGrid(n, n, 5.5 * a / n, 5.0 * a / n, -1.25 * a, 0.0)
    X, Y = grid.coordinates()
    return geometry.contact_modulus, grid, (X**2 + Y**2) / (2 * RX)


EHL_VALID = dict(n=st.sampled_from([16, 24, 32]), load=real(5.0, 25.0), u=real(0.5, 2.0), eta0=real(0.02, 0.1),
                 film=real(1e-7, 5e-7), du=real(-1.0, 1.0), tau0=positive(1e6, 1e8))


EHL_BAD = dict(load=st.sampled_from([0.0, -1.0, 1e-17, 1e6]), u=st.sampled_from([0.0, -1.0, 1e-300, 1e300]),
               eta0=st.sampled_from([0.0, 1e300, 1e-300]), film=st.sampled_from([0.0, 1e-300, 1.0]),
               du=st.sampled_from([0.0, 1e300]), tau0=st.sampled_from([0.0, 1e-300]))
