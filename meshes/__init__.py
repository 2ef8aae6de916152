"""gmsh geometry builders for balls, grooves, rails and screw/nut segments.

gmsh is imported inside the builders, never at package import.  Builders write
a cached ``.msh`` (gmsh 4.1) with named physical groups and return its path;
``fem`` loads it with ``skfem.MeshTet.load``.  Cache: ``lowmodel.cache``.
"""
