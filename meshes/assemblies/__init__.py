"""Assemblies: meshes of two or more bodies built from the parts of :mod:`meshes.parts`.

- ``meshes.assemblies.contact_pairs``: ball on flat, ball on ball, ball in a straight groove
- ``meshes.assemblies.screw_pair``: ball in a helical screw or nut groove (one flank)
- ``meshes.assemblies.fourpoint_module``: linear-bearing four-point module (two rails, one or two balls)
- ``meshes.assemblies.ball_screw_module``: ball-screw module (screw, nut, one or two balls)
"""
