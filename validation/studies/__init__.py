"""Validation studies: the run logic that several scenes, ``calibrate``, ``show`` and the sweeps share, as
plain functions of a case (:mod:`ballbench.validation.cases`).

A scene module holds only its ``@scene`` functions; what they compute with more than a few lines, and what
anything else needs, lives here: :mod:`.fe_contact` (FE of one contact against Hertz), :mod:`.screw_two_ball`
(the two-ball ball-screw module, its fitted preload), :mod:`.fe_b2b_linear` and :mod:`.fe_b2b_screw` (FE
modules and FE-informed B2B), :mod:`.sun2021` (the sun2021 contact load, dry contact and EHL domain),
:mod:`.calibration` (the one calibration home of validation: the ``calibrate`` spec, FE load sweeps and
contact laws, the command and ``--calibration FILE``, the synthetic round trip of the fits).
"""
