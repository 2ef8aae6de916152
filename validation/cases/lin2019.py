"""Lin, Duan, Okwudire (2019), J. Tribol. 141: the linear guide of Table 1, the ball screw of Table 4 and their
cases (Sec 2.4, Tables 2-3; Sec 3.3, Table 5; Sec 3.4), with the FE settings of the scenes that check them, SI.

The printed values and units are in the comments; the conversion happens here, nowhere else.  The paper's
printed results are references (:mod:`ballbench.validation.references.published.lin2019`).  The extracted
text has known defects (papers/README.md: Table 2 columns merged, Table 4's "210 N/mm^2").
"""
from __future__ import annotations

import math

from ballbench.meshes.parts.groove_segment import BODY_DEPTH
from ballbench.validation.cases.case import (BallScrew, BallScrewCase, ContactCase, ContactFe, Fit, LinearGuide,
                                             LinearGuideCase, Material, MeshLevels, ModuleFe, ModuleLevel, PairLevel)

# --------------------------------------------------------------------------
# Table 1: the linear guide
# --------------------------------------------------------------------------
STEEL = Material(youngs_modulus=2.1e11,  # E [Pa]     printed 2.1e11 N/m^2 (Table 4: "210 N/mm^2", a typo)
                 poisson_ratio=0.28)     # nu [-]     printed 0.28
GUIDE = LinearGuide(ball_radius=5e-3,             # R_B [m]    printed 5 mm
                    conformity=0.56,              # conf. [-]  printed 0.56
                    nominal_angle=math.pi / 4,    # beta_0 [rad], printed 45 deg (Sec 2.4)
                    material=STEEL,
                    friction_coefficient=0.1,     # mu [-]     printed 0.1
                    groove_velocity=10e-3)        # v [m/s]    printed 10 mm/s
VERTICAL_FORCE = 100.0                            # N_y [N]    printed 100 N
THETA = math.radians(2.0)                         # contact angle deviation [rad], printed 2 deg (Sec 2.4, Fig 7)
SIDE_FORCE_RATIO = -0.6                           # rho = N_x / N_y [-], printed -0.6

# FE four-point module of each ball (fem.fourpoint): h_contact in the elliptic slab of each contact (multiples of
# its Hertz a, b, b at the eq 36 force, the larger of the two balls), growth beyond it; the slab sizes and the
# level table are measured in docs/fe_b2b.md ("Fine zones").  The candidate zone reaches 6 um of initial gap: the
# largest approach is 3.1 um, and the coarse growth zone about the ends of the major axes needs the margin.
GUIDE_FE = ModuleFe(
    levels=MeshLevels(quick=(ModuleLevel(4.0e-5, 1.4, None),),
                      default=(ModuleLevel(3.0e-5, 1.35, None),),
                      fine=(ModuleLevel(5.0e-5, 1.45, None), ModuleLevel(4.0e-5, 1.4, None),
                            ModuleLevel(3.0e-5, 1.35, None), ModuleLevel(2.5e-5, 1.35, None))),
    gap_limit=6e-6, fine_ellipse=(0.6, 1.3, 0.5))

# Tables 2-3: two touching balls, bottom groove (-theta, +theta); case (b) mitigates with the top groove
TABLE3_A = LinearGuideCase("lin2019 Tables 2-3 case (a)", GUIDE, VERTICAL_FORCE, SIDE_FORCE_RATIO,
                           (-THETA, THETA, 0.0, 0.0), fe=GUIDE_FE)
TABLE3_B = LinearGuideCase("lin2019 Tables 2-3 case (b), mitigating top groove", GUIDE, VERTICAL_FORCE,
                           SIDE_FORCE_RATIO, (-THETA, THETA, -THETA, THETA), fe=GUIDE_FE)
TABLE3 = {"a": TABLE3_A, "b": TABLE3_B}

# --------------------------------------------------------------------------
# Table 4: the ball screw, and the preload fitted on Table 5 case (a)
# --------------------------------------------------------------------------
# Table 4 gives no preload.  The oversize is fitted on case (a)'s low-order B2B force alone (docs/ball_screw.md,
# "Preload"); studies.screw_two_ball.fit_oversize fits it again, and tests/test_cases.py checks that it still
# gives this value.
OVERSIZE_FIT = Fit(target="lin2019 Table 5 case (a), low-order numerical F_B2B = 1.92 N (tilted deviation reading, "
                          "Hertz contacts)",
                   method="brentq on the oversize in [1e-6, 3e-6] m, xtol 1e-12 m")
SCREW = BallScrew(ball_radius=2.778e-3,             # R_B [m]       printed 2.778 mm
                  pitch_radius=16.5e-3,             # R_P [m]       printed 16.5 mm
                  lead=20e-3,                       # p [m]         printed 20 mm
                  nominal_angle=math.radians(45.0),  # beta_0 [rad] printed 45 deg
                  conformity=0.56,                  # conf. [-]     printed 0.56
                  material=STEEL,
                  friction_coefficient=0.1,         # mu [-]
                  nut_speed=2 * math.pi,            # omega_N [rad/s], printed 2 pi rad/s
                  oversize=1.6848340370165068e-06,  # [m], OVERSIZE_FIT
                  oversize_fit=OVERSIZE_FIT)
AXIAL_LOAD_TWO_BALL = 50.0                          # [N] on the screw, Sec 3.3

# FE screw module of each ball (fem.screw_module): a ball-shaped fine zone of fine_radius about each contact, which
# resolves the minor semi-axes b = 40-70 um (a = 185-290 um lie in the growth zone); h_max 1 mm far away, ANSYS's
# (Sec 3.3); screw core and nut outside at R_P -+ BODY_DEPTH R_B (docs/fe_b2b.md, "Depth of the FE bodies").
# The candidate zone (on the gap with the oversize subtracted) reaches 5 um: approaches 0.5-0.7 um + 1.7 um preload.
SCREW_FE = ModuleFe(
    levels=MeshLevels(quick=(ModuleLevel(4.0e-5, 1.5, 1.5e-4, 1.0e-3),),
                      default=(ModuleLevel(3.0e-5, 1.4, 1.5e-4, 1.0e-3),),
                      fine=(ModuleLevel(4.0e-5, 1.5, 1.5e-4, 1.0e-3), ModuleLevel(3.0e-5, 1.4, 1.5e-4, 1.0e-3),
                            ModuleLevel(2.2e-5, 1.35, 1.5e-4, 1.0e-3))),
    gap_limit=5e-6, body_depth=BODY_DEPTH)

# Table 5: ball 1 theta = 0, ball 2 theta = 2 deg (a) or 3 deg (b); Fig 17 (missing) read as "tilted"
TABLE5_A = BallScrewCase("lin2019 Table 5 case (a)", SCREW, AXIAL_LOAD_TWO_BALL, (0.0, math.radians(2.0)),
                         fe=SCREW_FE)       # printed 2 deg
TABLE5_B = BallScrewCase("lin2019 Table 5 case (b)", SCREW, AXIAL_LOAD_TWO_BALL, (0.0, math.radians(3.0)),
                         fe=SCREW_FE)       # printed 3 deg
TABLE5 = {"a": TABLE5_A, "b": TABLE5_B}

# Sec 3.4 (Figs 19-21): the whole screw
WHOLE_SCREW_LENGTH = 0.8                    # [m]  printed 800 mm
WHOLE_SCREW_BALLS = 37                      # "37 balls in two loaded turns"
WHOLE_SCREW_TURNS = 2                       # loaded turns
WHOLE_SCREW_AXIAL_LOAD = 1500.0             # [N]  printed 1500 N
WHOLE_SCREW_DURATION = 2.0                  # [s]  "2 s in 200 steps"
WHOLE_SCREW_STEPS = 200
WHOLE_SCREW_THETA_CYCLES = 4                # four cycles of theta over the two turns (Fig 19 missing)

# --------------------------------------------------------------------------
# single contacts of the FE Hertz benchmark: Table 1's ball and steel at N_y, and the Table 4 grooves
# --------------------------------------------------------------------------
# (n = b / h_contact, growth) per fidelity; the fine study has >= 4 levels.  Measured per level: docs/fem.md.
PAIR_LEVELS = MeshLevels(quick=(PairLevel(5.5, 1.4),), default=(PairLevel(6.0, 1.3),),
                         fine=(PairLevel(5.5, 1.4), PairLevel(6.0, 1.3), PairLevel(7.0, 1.25), PairLevel(8.0, 1.2)))
# conformity 0.56 with the elliptic fine zone: the same default level, 26 % fewer DOFs than the capsule
PAIR_LEVELS_ELLIPSE = MeshLevels(quick=(PairLevel(5.5, 1.4),), default=(PairLevel(6.0, 1.3),),
                                 fine=(PairLevel(5.5, 1.4), PairLevel(6.0, 1.3), PairLevel(7.0, 1.25),
                                       PairLevel(8.0, 1.25)))
# conformity 0.52: the most elongated ellipse (a/b = 8.1), b needs n = 6.5 at the default level
PAIR_LEVELS_052 = MeshLevels(quick=(PairLevel(5.5, 1.4),), default=(PairLevel(6.5, 1.3),),
                             fine=(PairLevel(5.5, 1.4), PairLevel(6.5, 1.3), PairLevel(7.0, 1.25),
                                   PairLevel(8.0, 1.25)))
# the helical pairs are full models (no symmetry): about 2.5x the DOFs of a quarter groove
PAIR_LEVELS_SCREW = MeshLevels(quick=(PairLevel(5.5, 1.6),), default=(PairLevel(6.0, 1.45),),
                               fine=(PairLevel(5.5, 1.6), PairLevel(6.0, 1.45), PairLevel(6.5, 1.4),
                                     PairLevel(7.0, 1.35)))
# circular contacts have as many elements across a as across b: finer n at the same cost
PAIR_LEVELS_CIRCULAR = MeshLevels(quick=(PairLevel(6.0, 1.4),), default=(PairLevel(10.0, 1.3),),
                                  fine=(PairLevel(6.0, 1.4), PairLevel(8.0, 1.3), PairLevel(10.0, 1.3),
                                        PairLevel(12.0, 1.25), PairLevel(14.0, 1.2)))
# fine zones (ContactFe.zone): the elliptic slab (1.2 a, 1.3 b, 0.8 b) holds the 1.5 F contact of the load sweep
# (a, b x 1.145); the capsules about the major axis: (radius / b, half-length / a)
ELLIPSE_ZONE = (1.2, 1.3, 0.8)
FE_CIRCULAR = ContactFe(PAIR_LEVELS_CIRCULAR, "capsule", (1.3, 0.0))
FE_SCREW_GROOVE = ContactFe(PAIR_LEVELS_SCREW, "capsule", (1.2, 1.0))
# the finest level of the 0.56 groove is to reach a, b within 0.2 % and p0 within 0.3 % of Hertz (docs/fem.md)
FINE_TARGETS_056 = (("a", 0.002), ("b", 0.002), ("p0", 0.003))


def _groove(conformity: float, fe: ContactFe) -> ContactCase:
    return ContactCase(f"ball in a straight groove, conformity {conformity:g}", "groove", GUIDE.ball_radius, STEEL,
                       VERTICAL_FORCE, conformity=conformity, fe=fe)


CONTACT_FLAT = ContactCase("ball on a flat", "flat", GUIDE.ball_radius, STEEL, VERTICAL_FORCE, fe=FE_CIRCULAR)
CONTACT_BALL = ContactCase("ball on ball", "ball", GUIDE.ball_radius, STEEL, VERTICAL_FORCE, fe=FE_CIRCULAR)
CONTACT_GROOVE_052 = _groove(0.52, ContactFe(PAIR_LEVELS_052, "ellipse", ELLIPSE_ZONE))
CONTACT_GROOVE_056 = _groove(0.56, ContactFe(PAIR_LEVELS_ELLIPSE, "ellipse", ELLIPSE_ZONE,
                                             fine_targets=FINE_TARGETS_056))
CONTACT_GROOVE_060 = _groove(0.60, ContactFe(PAIR_LEVELS, "capsule", (1.4, 1.1)))
CONTACT_SCREW = ContactCase("ball in the helical screw groove of Table 4", "screw", SCREW.ball_radius, STEEL,
                            VERTICAL_FORCE, screw=SCREW, fe=FE_SCREW_GROOVE)
CONTACT_NUT = ContactCase("ball in the helical nut groove of Table 4", "nut", SCREW.ball_radius, STEEL,
                          VERTICAL_FORCE, screw=SCREW, fe=FE_SCREW_GROOVE)
