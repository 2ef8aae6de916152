"""Lin, Duan, Okwudire (2019), J. Tribol. 141: the linear guide of Table 1, the ball screw of Table 4 and their
cases (Sec 2.4, Tables 2-3; Sec 3.3, Table 5; Sec 3.4), with the FE settings of the scenes that check them, SI.

The cases are case files (``validation/cases/files/lin2019-*.toml``, read by :mod:`.case_file` through the one
units parser): each holds the printed values with their printed units and the reason of every FE setting; this
module reads them once and names their parts for the scenes, studies and sweeps.  The paper's printed results are
references (:mod:`ballbench.validation.references.published.lin2019`).  The extracted text has known defects
(papers/README.md: Table 2 columns merged, Table 4's "210 N/mm^2").
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ballbench.lowmodel.bearing import GuideLoadCase
from ballbench.validation.cases.case_file import load

FILES = Path(__file__).parent / "files"


def _file(name: str):
    return load(FILES / f"lin2019-{name}.toml")


def _shared(case, field: str, part):
    """``case`` holding the very object ``part`` as its ``field`` (the files repeat Table 1 or Table 4; they must
    agree, and the cases then share one object as they did when declared in Python)."""
    if getattr(case, field) != part:
        raise ValueError(f"{case.name}: its {field} differs from the one of the first file that gives it")
    return replace(case, **{field: part})


# --------------------------------------------------------------------------
# Tables 1-3: the linear guide and the two-ball cases (a) and (b), with the FE four-point module levels
# --------------------------------------------------------------------------
TABLE3_A = _file("table3-a")            # bottom groove (-theta, +theta), exact top groove
TABLE3_B = _shared(_file("table3-b"), "guide", TABLE3_A.guide)  # case (b): the mitigating top groove
TABLE3 = {"a": TABLE3_A, "b": TABLE3_B}
GUIDE = TABLE3_A.guide                  # Table 1: R_B 5 mm, conformity 0.56, beta_0 45 deg, mu 0.1, v 10 mm/s
STEEL = GUIDE.material                  # E 2.1e11 Pa, nu 0.28
VERTICAL_FORCE = TABLE3_A.vertical_force  # N_y [N], printed 100 N
THETA = TABLE3_A.theta                  # contact angle deviation [rad], printed 2 deg (Sec 2.4, Fig 7)
SIDE_FORCE_RATIO = TABLE3_A.side_force_ratio  # rho = N_x / N_y [-], printed -0.6
GUIDE_FE = TABLE3_A.fe                  # FE four-point module levels (docs/fe_b2b.md, "Fine zones")


def module_case(theta: float, rho: float, *, top=(0.0, 0.0), n_balls: int = 2, vertical_force: float = VERTICAL_FORCE,
                **guide) -> GuideLoadCase:
    """The setup of Sec 2.4 (Fig 7) on the Table 1 guide, for the paper figures that sweep it: bottom groove
    ``(-theta, +theta)`` [rad], top groove ``top`` = (TR, TL) [rad], ``rho`` = N_x / N_y of ball 1, ``n_balls`` balls
    under ``vertical_force`` [N] each; ``guide``: fields of Table 1's :class:`lowmodel.bearing.LinearGuide` changed
    (e.g. ``friction_coefficient``; ``youngs_modulus`` and ``poisson_ratio`` change its material).  The models take
    it as they take a case file's case (``lowmodel.linear_bearing.b2b.contacts``)."""
    material = {k: guide.pop(k) for k in ("youngs_modulus", "poisson_ratio") if k in guide}
    if material:
        guide["material"] = replace(GUIDE.material, **material)
    return GuideLoadCase(replace(GUIDE, **guide) if guide else GUIDE, vertical_force, rho,
                         (-theta, theta, top[0], top[1]), n_balls)

# --------------------------------------------------------------------------
# Table 4: the ball screw, the preload fitted on Table 5 case (a), and Table 5's cases
# --------------------------------------------------------------------------
TABLE5_A = _file("table5-a")            # ball 1 theta = 0, ball 2 theta = 2 deg; Fig 17 read as "tilted"
TABLE5_B = _shared(_file("table5-b"), "screw", TABLE5_A.screw)  # ball 2 theta = 3 deg
TABLE5 = {"a": TABLE5_A, "b": TABLE5_B}
SCREW = TABLE5_A.screw                  # Table 4, with the fitted oversize 1.6848 um
OVERSIZE_FIT = SCREW.oversize_fit       # how the oversize was fitted (tests/test_cases.py fits it again)
AXIAL_LOAD_TWO_BALL = TABLE5_A.axial_load  # [N] on the screw, Sec 3.3
SCREW_FE = TABLE5_A.fe                  # FE screw module levels (docs/fe_b2b.md)

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
CONTACT_FLAT = _file("contact-flat")
CONTACT_BALL = _file("contact-ball")
CONTACT_GROOVE_052 = _file("contact-groove-052")
CONTACT_GROOVE_056 = _file("contact-groove-056")
CONTACT_GROOVE_060 = _file("contact-groove-060")


CONTACT_SCREW = _shared(_file("contact-screw"), "screw", SCREW)
CONTACT_NUT = _shared(_file("contact-nut"), "screw", SCREW)
# their FE settings, named for the scenes and docs (n = b / h_contact, growth; measured per level: docs/fem.md)
PAIR_LEVELS = CONTACT_GROOVE_060.fe.levels          # capsule fine zone
PAIR_LEVELS_ELLIPSE = CONTACT_GROOVE_056.fe.levels  # the elliptic fine zone: 26 % fewer DOFs than the capsule
PAIR_LEVELS_052 = CONTACT_GROOVE_052.fe.levels      # the most elongated ellipse (a/b = 8.1): n = 6.5 at default
PAIR_LEVELS_SCREW = CONTACT_SCREW.fe.levels         # helical pairs: full models, no symmetry
PAIR_LEVELS_CIRCULAR = CONTACT_FLAT.fe.levels       # circular contacts: finer n at the same cost
ELLIPSE_ZONE = CONTACT_GROOVE_056.fe.zone           # (1.2 a, 1.3 b, 0.8 b): holds the 1.5 F contact of the sweep
FE_CIRCULAR = CONTACT_FLAT.fe
FE_SCREW_GROOVE = CONTACT_SCREW.fe
FINE_TARGETS_056 = CONTACT_GROOVE_056.fe.fine_targets  # a, b within 0.2 %, p0 within 0.3 % at the finest level
