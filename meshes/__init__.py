"""gmsh geometry builders for balls, grooves, rails and screw/nut segments.

gmsh is imported inside the builders, never at package import.  Builders write
a cached ``.msh`` (gmsh 4.1) with named physical groups and return its path;
``fem`` loads it.  Cache: ``lowmodel.cache``.  Exact geometry (helix, groove
profiles, contact frames, curvatures) comes from the geometry core; meshes builds
solids from it.  Layout:

Tools
- ``meshes.gmsh_tools``: gmsh session, cached build, atomic write, physical groups, VTU export
- ``meshes.refinement``: the mesh-size growth law, its fine zones (point, segment, box),
  the uniform fallback and the checks of their arguments
- ``meshes.snapping``: mesh nodes moved onto the exact helical groove surfaces

Parts (``meshes.parts``)
- ``ball``: a ball split into contact caps
- ``rail``: straight gothic-arch rail segment with per-side contact angle deviations
- ``groove_segment``: screw or nut segment with its helical gothic-arch groove
- ``groove_block``: helical block around one flank's contact

Assemblies (``meshes.assemblies``)
- ``contact_pairs``: ball on flat, ball on ball, ball in a straight groove (Hertz scenes)
- ``screw_pair``: ball in a helical screw or nut groove
- ``fourpoint_module``: linear-bearing four-point module (rails and one or two balls)
- ``ball_screw_module``: ball-screw module (screw, nut and one or two balls)

The contact-pair convention (frame and group names) is in docs/developing.md;
docs/meshes.md describes the builders.
"""
