"""gmsh geometry builders for balls, grooves, rails and screw/nut segments.

gmsh is imported inside the builders, never at package import.  Builders write
a cached ``.msh`` (gmsh 4.1) with named physical groups and return its path;
``fem`` loads it.  Cache: ``lowmodel.cache``.  Modules:

- ``meshes.gmsh_tools``: gmsh session, cached build, contact size fields, groups, VTU export
- ``meshes.contact_pairs``: ball on flat, ball on ball, ball in a straight groove (Hertz scenes)
- ``meshes.helical``: helical screw/nut groove geometry and the ball-in-screw-groove pair
- ``meshes.rail``: straight gothic-arch rail segment with per-side contact angle deviations
- ``meshes.fourpoint_module``: linear-bearing four-point module (rails and one or two balls)
- ``meshes.helical_module``: ball-screw module (screw, nut and one or two balls)

The contact-pair convention (frame and group names) is in docs/developing.md.
"""
