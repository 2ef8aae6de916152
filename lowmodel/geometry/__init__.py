"""Geometry core shared by the models (``lowmodel``) and the mesh builders (``meshes``); numpy only.

- :mod:`.helix`: the ball-centre helix (wang2022 eq 10, lin2019 eq 35), the lead
  angle (one name, ``lead_angle``), the Frenet frame CS1 (wang2022 eq 9) and
  lin2019's CS3 (eq 41);
- :mod:`.groove`: gothic-arch groove profiles, straight (rail) and helical (screw,
  nut), the exact swept surface and its principal curvatures (fundamental forms);
- :mod:`.fourpoint`: lin2017 eq 1 contact normals and points in the order
  ``CONTACT_NAMES = (BL, BR, TR, TL)``.

Each formula lives here once; models and meshes import it.
"""
