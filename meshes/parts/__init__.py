"""Parts: OCC bodies added to an open gmsh model, and the builders of single parts.

- ``meshes.parts.ball``: a ball split into contact caps (four-point and ball-screw modules)
- ``meshes.parts.rail``: straight gothic-arch rail (OCC body, face roles, ``rail_segment`` builder)
- ``meshes.parts.groove_segment``: screw or nut segment with its helical gothic-arch groove
  (OCC body, face roles, node snapping, ``screw_groove_segment`` builder)
- ``meshes.parts.groove_block``: the helical block around one flank's contact (counter body
  of the ball-in-screw-groove pair)
"""
