"""Low-order and analytical models of ball bearings and ball screws.

numpy/scipy only; importing this package must stay light (no gmsh, pyvista,
vtk or matplotlib at import time).  One module per model:

- ``lowmodel.hertz``: exact Hertz point contact (Johnson 1985; lin2019 eqs 15, 53)
- ``lowmodel.fourpoint``: rigid four-point rolling/sliding (lin2017)
"""
