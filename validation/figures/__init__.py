"""Figures of the validation scenes: matplotlib plots and pyvista 3D screenshots of saved fields."""
