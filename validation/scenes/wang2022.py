"""Scenes for ball-screw contact kinematics with the Frenet frame as a virtual cage (wang2022).

Models: lowmodel.screw.kinematics (present model, Wei's absolute-velocity
measures), lowmodel.ball_bearing.harris (ball bearing).  Inputs in the paper's units are
converted to SI here.
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.ball_bearing import harris
from ballbench.lowmodel.screw import kinematics as sk
from ballbench.validation.cases import wang2022 as case
from ballbench.validation.figures import wang2022 as figures
from ballbench.validation.references.published import wang2022 as published
from ballbench.validation.scene import scene

MODEL = "lowmodel.screw.kinematics"
RPM = case.RPM  # rad/s per rpm
HALF_UNIT = published.HALF_UNIT  # wang2022 Tables 1-2 print 3 decimals

# wang2022 Table A1 as keyword arguments of lowmodel.screw.kinematics (r_m = d_m/2, r_b = d_b/2; papers/README.md)
TABLE_A1 = dict(pitch_radius=case.SCREW.pitch_radius, ball_radius=case.SCREW.ball_radius, lead=case.SCREW.lead,
                screw_speed=case.SCREW.screw_speed, contact_angle_nut=case.SCREW.nominal_angle)
BALL_MASS = case.SCREW.ball_mass  # kg, Table A1
PRINTED_LEAD_ANGLE = published.LEAD_ANGLE  # Table A1

# wang2022 Table 2, present model (Frenet components t, n, b) and Wei's model
TABLE2_PRESENT_VECTORS = published.TABLE2.present_vectors
TABLE2_PRESENT_SCALARS = published.TABLE2.present_scalars
TABLE2_WEI_VECTORS = published.TABLE2.wei_vectors
TABLE2_WEI_SCALARS = published.TABLE2.wei_scalars
# wang2022 Table 1 (61830 deep-groove ball bearing, inner ring at 3600 rpm)
TABLE1 = {"present": published.TABLE1.present, "wei_U_A": published.TABLE1.wei_U_A,
          "wei_U_B": published.TABLE1.wei_U_B, "wei_S_A": published.TABLE1.wei_S_A,
          "wei_S_B": published.TABLE1.wei_S_B}
BEARING_SPEED = case.BEARING_INNER_RING_SPEED
COMPONENTS = ("t", "n", "b")
PRINTED_WHY = "printed to 3 decimals: half a unit (0.0005) is an absolute tolerance, judged on the scale 1"


def _printed_tolerance(reference: float) -> tuple[float, float]:
    """(tolerance, scale) for half a unit of the 3rd decimal on the error convention of run.check."""
    scale = 1.0
    return HALF_UNIT / max(abs(reference), scale), scale


def _check_printed(run, *, quantity, unit, value, reference, source, time_s, model=MODEL, note=""):
    tolerance, scale = _printed_tolerance(reference)
    run.check(model=model, family="analytical", quantity=quantity, unit=unit, value=value, reference=reference,
              source=source, tolerance=tolerance, scale=scale, time_s=time_s, note=note, why=PRINTED_WHY)


def _wei_measures(vectors: dict[str, np.ndarray]) -> dict[str, float]:
    """U, S and V_S of Wei's model from absolute vectors (wang2022 eqs 1-6)."""
    u_a, v_sa, s_a = sk.absolute_velocity_measures(vectors["V_An^a"], vectors["V_Ab^a"], raceway_is_driver=False)
    u_b, v_sb, s_b = sk.absolute_velocity_measures(vectors["V_Bs^a"], vectors["V_Bb^a"], raceway_is_driver=True)
    out = {"U_A": float(u_a), "U_B": float(u_b), "S_A": float(s_a), "S_B": float(s_b)}
    for index, component in enumerate(COMPONENTS):
        out[f"V_SA {component}"] = float(v_sa[index])
        out[f"V_SB {component}"] = float(v_sb[index])
    return out


def _rounding_bound(vectors: dict[str, tuple]) -> dict[str, float]:
    """First-order worst case of each Wei measure when every printed input moves by half a unit.

    Plus half a unit for the rounding of the printed output itself.
    """
    base = {key: np.array(value, dtype=float) for key, value in vectors.items()}
    nominal = _wei_measures(base)
    bound = {key: HALF_UNIT for key in nominal}
    step = 1e-7
    for key in ("V_An^a", "V_Ab^a", "V_Bs^a", "V_Bb^a"):
        for index in range(3):
            moved = {k: v.copy() for k, v in base.items()}
            moved[key][index] += step
            shifted = _wei_measures(moved)
            for name in bound:
                bound[name] += abs(shifted[name] - nominal[name]) / step * HALF_UNIT
    return bound


@scene("wang2022-table2",
       "Ball screw of wang2022 Table A1 at 2000 rpm: every vector and scalar of Table 2 (present model, "
       "Frenet frame as virtual cage); Wei's column as far as its equations define it", kind="analytical", cost_s=0.1)
def wang2022_table2(run):
    result, time_s = run.time(sk.kinematics, **TABLE_A1)
    source = "wang2022 Table 2 (present model), inputs Table A1"
    for (symbol, attribute), printed in TABLE2_PRESENT_VECTORS.items():
        value = getattr(result, attribute)
        for index, component in enumerate(COMPONENTS):
            _check_printed(run, quantity=f"{symbol} {component}", unit="m/s", value=value[index],
                           reference=printed[index], source=source, time_s=time_s)
    for (symbol, attribute, unit), printed in TABLE2_PRESENT_SCALARS.items():
        _check_printed(run, quantity=symbol, unit=unit, value=getattr(result, attribute), reference=printed,
                       source=source, time_s=time_s)

    # the printed lead angle 8.74 deg instead of arctan(L / 2 pi r_m) = 8.742 deg
    printed_psi = sk.kinematics(**TABLE_A1, lead_angle=PRINTED_LEAD_ANGLE)
    worst = 0.0
    for (_, attribute), printed in TABLE2_PRESENT_VECTORS.items():
        worst = max(worst, float(np.max(np.abs(getattr(printed_psi, attribute) - printed))))
    for (_, attribute, _), printed in TABLE2_PRESENT_SCALARS.items():
        worst = max(worst, abs(float(getattr(printed_psi, attribute)) - printed))
    run.check(model=MODEL, family="analytical",
              quantity="worst |deviation| from Table 2 (present) with psi = 8.74 deg as printed",
              unit="m/s or 1", value=worst, reference=HALF_UNIT, relation="le", source="wang2022 Table 2, A1",
              tolerance=0.0, time_s=time_s, note="upper bound: half a unit of the printed 3rd decimal")

    # ---- Wei's model ---------------------------------------------------
    wei, wei_time = run.time(sk.wei_ball_centre_kinematics, **TABLE_A1)
    source_w = "wang2022 Table 2 (Wei's model)"
    for index, component in enumerate(COMPONENTS):
        _check_printed(run, model=MODEL + " (Wei)", quantity=f"Wei V_An^a {component}", unit="m/s",
                       value=wei.nut_velocity[index], reference=TABLE2_WEI_VECTORS["V_An^a"][index],
                       source=source_w + "; eq 16", time_s=wei_time)
    for index, component in ((0, "t"), (2, "b")):
        _check_printed(run, model=MODEL + " (Wei)", quantity=f"Wei V_Bs^a {component}", unit="m/s",
                       value=wei.screw_velocity[index], reference=TABLE2_WEI_VECTORS["V_Bs^a"][index],
                       source=source_w + "; eq 17", time_s=wei_time)
    _check_printed(run, model=MODEL + " (Wei)", quantity="Wei |V_Bs^a n| (printed with the opposite sign)",
                   unit="m/s", value=abs(wei.screw_velocity[1]), reference=abs(TABLE2_WEI_VECTORS["V_Bs^a"][1]),
                   source=source_w + "; eq 17", time_s=wei_time,
                   note="Wei's column prints -0.071, eq 17 and the present column +0.071: sign of Wei's derivation")
    # the part of Wei's ball velocities that the equations define: the ball-centre velocity
    mean_ball = 0.5 * (np.array(TABLE2_WEI_VECTORS["V_Ab^a"]) + TABLE2_WEI_VECTORS["V_Bb^a"])
    for index, component in enumerate(COMPONENTS):
        _check_printed(run, model=MODEL + " (Wei)", quantity=f"Wei (V_Ab^a + V_Bb^a)/2 {component} = ball-centre "
                       "velocity", unit="m/s", value=wei.ball_velocity_nut[index], reference=mean_ball[index],
                       source=source_w + " (mean of the two printed ball vectors); d/dt of eq 10, eq 18",
                       time_s=wei_time, note="tolerance: half a unit of the printed 3rd decimal (mean of two)")
    # U, V_S, S of Wei's column from the table's own vectors (eqs 1-6 with absolute velocities)
    table_vectors = {key: TABLE2_WEI_VECTORS[key] for key in ("V_An^a", "V_Ab^a", "V_Bs^a", "V_Bb^a")}
    measures, measure_time = run.time(_wei_measures, {k: np.array(v) for k, v in table_vectors.items()})
    bound = _rounding_bound(table_vectors)
    printed = dict(TABLE2_WEI_SCALARS)
    for index, component in enumerate(COMPONENTS):
        printed[f"V_SA {component}"] = TABLE2_WEI_VECTORS["V_SA"][index]
        printed[f"V_SB {component}"] = TABLE2_WEI_VECTORS["V_SB"][index]
    for name, reference in printed.items():
        unit = "1" if name.startswith("S_") else "m/s"
        scale = 1.0
        run.check(model=MODEL + " (Wei measures)", family="analytical",
                  quantity=f"Wei {name} from the table's own vectors", unit=unit,
                  value=measures[name], reference=reference, source=source_w + "; eqs 1-6 on its V^a vectors",
                  tolerance=bound[name] / max(abs(reference), scale), scale=scale, time_s=measure_time, why=PRINTED_WHY,
                  note=f"tolerance: first-order rounding bound of the printed inputs + half a unit "
                       f"(+-{bound[name]:.4f})")
    delta = 0.5 * (TABLE2_WEI_VECTORS["V_Bb^a"][0] - TABLE2_WEI_VECTORS["V_Ab^a"][0])
    run.note("Tolerance of rows compared with a printed entry: half a unit of the 3rd decimal (absolute "
             "0.0005, i.e. relative 0.0005 / max(|reference|, 1)).")
    run.note("Present model: psi = arctan(L / 2 pi r_m) = %.4f deg (Table A1 prints 8.74 deg; both reproduce "
             "Table 2), beta = %.3f deg (eq 21), omega_m = %.3f rad/s (eq 18), omega_R = %.2f rad/s (eq 19); "
             "r_m = d_m/2 and r_b = d_b/2 (the nomenclature's 'diameter' is a radius)."
             % (np.degrees(result.lead_angle), np.degrees(result.pitch_angle), result.orbital_speed,
                result.spin_speed))
    run.note("Gap, Wei's ball surface velocities: wang2022 does not give Wei's expressions. What its equations "
             "define is checked above: the mean of Wei's V_Ab^a and V_Bb^a is the ball-centre velocity (d/dt of "
             f"eq 10 with eq 18), n = 0, b = nut b. The antisymmetric t-term, -/+{delta:.3f} m/s at A/B, cannot "
             "be derived. With it set to zero (lowmodel.screw.kinematics.wei_ball_centre_kinematics) Wei's "
             f"measures are U_A = {float(wei.entrainment_nut):.3f}, U_B = {float(wei.entrainment_screw):.3f} m/s, "
             f"S_A = {float(wei.slide_roll_nut):.3f}, S_B = {float(wei.slide_roll_screw):.3f} (table: 1.071, "
             "2.937, 1.766, 0.648); they are reported, not checked.")


@scene("wang2022-table1",
       "Deep-groove ball bearing 61830 (lead 0) at 3600 rpm: present model = Harris = 15.994 m/s, S = 0; "
       "Wei's model as far as its equations define it (wang2022 Table 1)", kind="analytical", cost_s=0.1)
def wang2022_table1(run):
    alpha = case.BEARING_CONTACT_ANGLE  # wang2022 Sec 3.1: alpha_i = alpha_o = pi/4
    # Geometry implied by Table 1 itself (the 61830 data of ref [21] are not given):
    #   present U = omega r_m (1 - gamma^2) / 2 and, in Wei's model with a ball velocity along t,
    #   U_A + U_B = omega r_m (1 - gamma) (the ball term cancels), gamma = r_b cos(alpha) / r_m.
    def implied_geometry(present_u, wei_sum):
        one_minus_g2 = 2 * present_u / BEARING_SPEED
        one_minus_g = wei_sum / BEARING_SPEED
        gamma = one_minus_g2 / one_minus_g - 1.0
        r_m = one_minus_g / (1.0 - gamma)
        return r_m, gamma * r_m / np.cos(alpha)

    implied_r_m, implied_r_b = implied_geometry(TABLE1["present"], TABLE1["wei_U_A"] + TABLE1["wei_U_B"])
    # rounding interval: every printed entry moved by +-half a unit (the sum of two by +-one unit)
    corners = [implied_geometry(TABLE1["present"] + du, TABLE1["wei_U_A"] + TABLE1["wei_U_B"] + ds)
               for du in (-HALF_UNIT, HALF_UNIT) for ds in (-2 * HALF_UNIT, 2 * HALF_UNIT)]
    r_m_bound = max(abs(c[0] - implied_r_m) for c in corners)
    r_b_bound = max(abs(c[1] - implied_r_b) for c in corners)
    pitch_radius, ball_radius = 0.085, 0.005  # d_m = (150 + 190)/2 = 170 mm (61830 bore/OD), D = 10 mm
    run.check(model="Table 1 geometry", family="analytical",
              quantity="d_m implied by Table 1", unit="m", value=2 * implied_r_m,
              reference=2 * pitch_radius, source="61830: (bore 150 mm + OD 190 mm) / 2",
              tolerance=r_m_bound / pitch_radius, time_s=0.0,
              note=f"from U (present) and U_A + U_B (Wei); tolerance: the rounding interval of Table 1, "
                   f"+-{2e3 * r_m_bound:.3f} mm")
    run.check(model="Table 1 geometry", family="analytical",
              quantity="d_b implied by Table 1 (alpha = 45 deg)", unit="m",
              value=2 * implied_r_b, reference=2 * ball_radius, source="10 mm ball chosen for the 61830",
              tolerance=r_b_bound / ball_radius, time_s=0.0,
              note=f"tolerance: the rounding interval of Table 1, +-{2e3 * r_b_bound:.3f} mm")

    present, time_p = run.time(sk.kinematics, pitch_radius, ball_radius, 0.0, BEARING_SPEED, alpha)
    bearing, time_h = run.time(harris.kinematics, pitch_radius, ball_radius, BEARING_SPEED, alpha)
    source = "wang2022 Table 1"
    for quantity, value, model, time_s in (
            ("U_A (outer)", present.entrainment_nut, MODEL, time_p),
            ("U_B (inner)", present.entrainment_screw, MODEL, time_p),
            ("U_A (outer)", bearing.entrainment_outer, "lowmodel.ball_bearing.harris", time_h),
            ("U_B (inner)", bearing.entrainment_inner, "lowmodel.ball_bearing.harris", time_h)):
        _check_printed(run, model=model, quantity=quantity, unit="m/s", value=value, reference=TABLE1["present"],
                       source=source, time_s=time_s)
    for quantity, value, model, time_s in (
            ("S_A", present.slide_roll_nut, MODEL, time_p), ("S_B", present.slide_roll_screw, MODEL, time_p),
            ("S_A", bearing.slide_roll_outer, "lowmodel.ball_bearing.harris", time_h),
            ("S_B", bearing.slide_roll_inner, "lowmodel.ball_bearing.harris", time_h)):
        run.check(model=model, family="analytical", quantity=quantity, unit="1", value=value, reference=0.0, scale=1.0,
                  why="S is a ratio of order 1: exact zero (lead 0) judged on the scale 1",
                  tolerance=1e-12, source=source + " (0.000); pure rolling", time_s=time_s,
                  note="exact zero expected (lead 0); tolerance 1e-12 on scale 1 for round-off")
    for quantity, value, reference in (
            ("U_A present vs Harris", present.entrainment_nut, bearing.entrainment_outer),
            ("U_B present vs Harris", present.entrainment_screw, bearing.entrainment_inner),
            ("omega_m present vs Harris cage speed", present.orbital_speed, bearing.cage_speed)):
        run.check(model=MODEL, family="analytical",
                  quantity=quantity, unit="m/s" if quantity[0] == "U" else "rad/s", value=value,
                  reference=reference, source="lowmodel.ball_bearing.harris (Harris & Kotzalas 2006)", tolerance=1e-12,
                  time_s=time_p, note="the two methods agree exactly at lead 0 (round-off only)")

    # ---- Wei's model -------------------------------------------------
    wei, time_w = run.time(sk.wei_ball_centre_kinematics, pitch_radius, ball_radius, 0.0, BEARING_SPEED, alpha)
    run.check(model=MODEL + " (Wei)", family="analytical", quantity="Wei S_A", unit="1", value=wei.slide_roll_nut,
              reference=TABLE1["wei_S_A"], source=source + "; eqs 1, 4, 5 with the outer ring at rest",
              tolerance=_printed_tolerance(2.0)[0], scale=1.0, time_s=time_w,
              note="= 2 for any ball velocity: |V_Ab| / (|V_Ab| / 2)")
    _check_printed(run, model=MODEL + " (Wei)", quantity="Wei U_A + U_B", unit="m/s",
                   value=wei.entrainment_nut + wei.entrainment_screw,
                   reference=TABLE1["wei_U_A"] + TABLE1["wei_U_B"], source=source + " (7.971 + 22.740)",
                   time_s=time_w, note="= omega r_m (1 - gamma): the unknown ball term cancels; tolerance: "
                                       "half a unit (each term +-0.0005 would allow 0.001)")
    screw_speed_abs = float(present.screw_velocity[0])  # eq 17, |V_Bs^a| at lead 0
    s_b_from_u_b = 2 * (screw_speed_abs - TABLE1["wei_U_B"]) / TABLE1["wei_U_B"]
    _check_printed(run, model=MODEL + " (Wei)", quantity="Wei S_B from the table's U_B and eq 17", unit="1",
                   value=s_b_from_u_b, reference=TABLE1["wei_S_B"],
                   source=source + "; eqs 2, 4, 6 with V_Bb^a = 2 U_B - V_Bs^a", time_s=time_w)
    delta_a = 2 * TABLE1["wei_U_A"] - float(wei.ball_velocity_nut[0])
    run.note("Tolerance of rows compared with a printed entry: half a unit of the 3rd decimal.")
    run.note("Geometry: the 61830 data of wang2022 ref [21] are not given. Table 1 itself fixes them: the "
             "present U = omega r_m (1 - gamma^2)/2 and Wei's U_A + U_B = omega r_m (1 - gamma) (ball term "
             f"cancels) give d_m = {2e3 * implied_r_m:.2f} mm, d_b = {2e3 * implied_r_b:.2f} mm at alpha = 45 deg; "
             "the scene uses d_m = 170 mm (= (150 + 190)/2 of a 61830) and d_b = 10 mm, which give "
             f"U = {float(present.entrainment_nut):.4f} m/s (15.994 printed).")
    run.note("Gap, Wei's U_A, U_B, S_B separately: they need Wei's ball surface velocity, which wang2022 does "
             f"not define. With the ball surface at the ball-centre velocity ({float(wei.ball_velocity_nut[0]):.3f}"
             f" m/s) Wei's model gives U_A = {float(wei.entrainment_nut):.3f}, U_B = "
             f"{float(wei.entrainment_screw):.3f} m/s, S_B = {float(wei.slide_roll_screw):.3f} (table 7.971, "
             f"22.740, 0.701); the table implies an extra t-term of +-{delta_a:.3f} m/s at A/B.")


@scene("wang2022-centrifugal",
       "Centrifugal force of a Table A1 ball at 3000 rpm: about 2 % of the 27 N mean contact load "
       "(wang2022 Sec 3.3, eq 22); nearly independent of the contact angle (Fig 4)", kind="analytical", cost_s=0.2)
def wang2022_centrifugal(run):
    def force(speed_rpm, alpha):
        state = sk.kinematics(**{**TABLE_A1, "screw_speed": speed_rpm * RPM, "contact_angle_nut": alpha})
        return state.centrifugal_force(BALL_MASS, TABLE_A1["pitch_radius"])

    value, time_s = run.time(force, 3000.0, np.radians(45.0))
    run.check(model=MODEL, family="analytical",
              quantity="F_n / 27 N at 3000 rpm", unit="1", value=float(value) / 27.0, reference=0.02,
              source="wang2022 Sec 3.3 ('only about 2 %')", tolerance=0.25, time_s=time_s,
              note="'about 2 %' read as one significant digit: [1.5, 2.5) %, i.e. 25 % of 2 %")
    angles = np.radians(np.linspace(35.0, 55.0, 21))
    spread_forces = force(3000.0, angles)
    spread = float(np.ptp(spread_forces) / np.mean(spread_forces))
    # with alpha_i = alpha_o the tan(beta) terms of eq 18 cancel: omega_m = omega (1 - gamma cos alpha) / 2
    gamma = TABLE_A1["ball_radius"] / TABLE_A1["pitch_radius"]
    closed = BALL_MASS * TABLE_A1["pitch_radius"] * (3000 * RPM * (1 - gamma * np.cos(angles)) / 2) ** 2
    run.check(model=MODEL, family="analytical",
              quantity="worst rel. deviation of F_n(alpha) from m r_m (omega (1 - gamma cos alpha)/2)^2",
              unit="1", value=float(np.max(np.abs(spread_forces / closed - 1))), reference=0.0, scale=1.0,
              why="the value is itself a relative deviation: zero judged on the scale 1",
              tolerance=1e-12, source="wang2022 eqs 18, 22 with alpha_i = alpha_o (closed form)", time_s=time_s,
              note="value is itself the worst relative deviation over alpha = 35-55 deg")
    ratio = float(force(3000.0, np.radians(45.0)) / force(1000.0, np.radians(45.0)))
    run.check(model=MODEL, family="analytical",
              quantity="F_n(3000 rpm) / F_n(1000 rpm)", unit="1", value=ratio, reference=9.0,
              tolerance=1e-12, source="wang2022 Sec 3.3 (speed 'greatly increases' F_n); eq 22: F_n ~ omega^2",
              time_s=time_s)
    run.note(f"Contact-angle effect (Fig 4, 'nearly constant'): F_n changes by {100 * spread:.1f} % over alpha = "
             "35-55 deg at 3000 rpm, against a factor 9 from 1000 to 3000 rpm; eq 18 gives "
             "F_n ~ (1 - gamma cos alpha)^2, gamma = r_b / r_m = 0.153. Reported, not checked: the paper gives no "
             "number for 'nearly constant'.")
    run.note(f"F_n = m r_m omega_m^2 (eq 22) with m = 1.05 g, r_m = 20.7 mm, omega_m = eq 18: "
             f"{float(value):.4f} N at 3000 rpm = {100 * float(value) / 27:.2f} % of 27 N.")

    speeds = np.linspace(0.0, 5000.0, 51)
    curves = {degrees: force(speeds, np.radians(degrees)) for degrees in (35, 40, 45, 50, 55)}
    run.save_figure(figures.centrifugal_force(speeds, curves), "fig4_centrifugal_force.png")


def _steps_against(values, sign) -> int:
    """Number of steps of ``values`` that go against the stated direction (sign +1 rising, -1 falling)."""
    return int(np.sum(np.sign(np.diff(values)) != sign))


@scene("wang2022-trends",
       "Parameter studies of wang2022 Figs 5-9 (screw speed, contact angle, lead, nominal diameter, ball "
       "diameter) around Table A1: the trends the paper states, and the figures", kind="analytical", cost_s=2.0)
def wang2022_trends(run):
    count = {"quick": 12, "default": 41, "fine": 201}[run.fidelity]
    source = "wang2022 Sec 3.4"
    studies = [
        ("screw_speed", np.linspace(100.0, 5000.0, count) * RPM, "screw speed [rpm]", 1 / RPM,
         "fig5_speed.png", "Fig 5: screw speed"),
        ("contact_angle_nut", np.radians(np.linspace(30.0, 60.0, count)), "contact angle [deg]", 180 / np.pi,
         "fig6_contact_angle.png", "Fig 6: contact angle"),
        ("lead", np.linspace(2e-3, 40e-3, count), "lead [mm]", 1e3, "fig7_lead.png", "Fig 7: lead"),
        ("pitch_radius", np.linspace(12e-3, 50e-3, count), "nominal diameter d_m [mm]", 2e3,
         "fig8_nominal_diameter.png", "Fig 8: nominal diameter"),
        ("ball_radius", np.linspace(1.5e-3, 5e-3, count), "ball diameter d_b [mm]", 2e3,
         "fig9_ball_diameter.png", "Fig 9: ball diameter"),
    ]
    results = {}
    for parameter, values, label, scale, filename, title in run.progress(studies, desc="Figs 5-9"):
        state, time_s = run.time(sk.kinematics, **{**TABLE_A1, parameter: values})
        results[parameter] = (values, state, time_s)
        run.save_figure(figures.trend_figure(values, label, state, f"wang2022 {title} (Table A1 otherwise)",
                                             scale, nominal=TABLE_A1[parameter]), filename)

    def count_check(quantity, value, statement, time_s):
        run.check(model=MODEL, family="analytical",
                  quantity=quantity, unit="count", value=value, reference=0.0, scale=1.0,
                  why="a count: zero judged on the scale of one",
                  tolerance=0.0, source=f"{source}: {statement}", time_s=time_s)

    def spread_check(quantity, array, statement, time_s):
        run.check(model=MODEL, family="analytical",
                  quantity=quantity, unit="1", value=float(np.ptp(array) / np.mean(np.abs(array))),
                  reference=0.0, scale=1.0, tolerance=1e-12, source=f"{source}: {statement}", time_s=time_s,
                  why="a relative spread: zero judged on the scale 1",
                  note="relative spread; exact zero up to round-off")

    values, state, time_s = results["screw_speed"]
    for side, u in (("A", state.entrainment_nut), ("B", state.entrainment_screw)):
        spread_check(f"spread of U_{side} / omega over speed", u / values, "U rises linearly with speed (Fig 5)",
                     time_s)
    for side, s in (("A", state.slide_roll_nut), ("B", state.slide_roll_screw)):
        spread_check(f"spread of S_{side} over speed", s, "S independent of speed (Fig 5)", time_s)
    count_check("points with S_A >= S_B or U_A >= U_B (speed sweep)",
                int(np.sum(state.slide_roll_nut >= state.slide_roll_screw)
                    + np.sum(state.entrainment_nut >= state.entrainment_screw)),
                "S and U slightly smaller on the nut side (Fig 5, conclusion 3)", time_s)

    values, state, time_s = results["contact_angle_nut"]
    count_check("steps against: S_B falls, S_A rises, U_A and U_B rise with alpha",
                _steps_against(state.slide_roll_screw, -1) + _steps_against(state.slide_roll_nut, +1)
                + _steps_against(state.entrainment_nut, +1) + _steps_against(state.entrainment_screw, +1),
                "contact angle (Fig 6)", time_s)
    run.check(model=MODEL, family="analytical", quantity="range of S_A / range of S_B over alpha 30-60 deg", unit="1",
              value=float(np.ptp(state.slide_roll_nut) / np.ptp(state.slide_roll_screw)), reference=1.0,
              relation="le", tolerance=0.0, source=f"{source}: S_A 'increases even less' (Fig 6)", time_s=time_s)
    run.check(model=MODEL, family="analytical", quantity="relative range of U_B over alpha 30-60 deg", unit="1",
              value=float(np.ptp(state.entrainment_screw) / np.mean(state.entrainment_screw)), reference=0.05,
              relation="le", tolerance=0.0, source=f"{source}: 'essentially negligible' (Fig 6)", time_s=time_s,
              note="'negligible' read as below 5 %")

    values, state, time_s = results["lead"]
    count_check("steps against: S_A, S_B and U_B rise, U_A falls with lead",
                _steps_against(state.slide_roll_nut, +1) + _steps_against(state.slide_roll_screw, +1)
                + _steps_against(state.entrainment_screw, +1) + _steps_against(state.entrainment_nut, -1),
                "lead (Fig 7)", time_s)
    run.check(model=MODEL, family="analytical", quantity="relative range of U_A, U_B over lead 2-40 mm (max)", unit="1",
              value=float(max(np.ptp(state.entrainment_nut) / np.mean(state.entrainment_nut),
                              np.ptp(state.entrainment_screw) / np.mean(state.entrainment_screw))),
              reference=0.05, relation="le", tolerance=0.0,
              source=f"{source}: lead has a 'negligible influence on entrainment velocity' (Fig 7)", time_s=time_s,
              note="'negligible' read as below 5 %")
    run.check(model=MODEL, family="analytical", quantity="S_B(lead 40 mm) / S_B(lead 2 mm)", unit="1",
              value=float(state.slide_roll_screw[-1] / state.slide_roll_screw[0]), reference=10.0, relation="ge",
              tolerance=0.0, source=f"{source}: S 'increases dramatically' with lead (Fig 7)", time_s=time_s,
              note="'dramatically' read as at least tenfold over a twentyfold lead")

    values, state, time_s = results["pitch_radius"]
    count_check("steps against: S falls, U rises with nominal diameter",
                _steps_against(state.slide_roll_nut, -1) + _steps_against(state.slide_roll_screw, -1)
                + _steps_against(state.entrainment_nut, +1) + _steps_against(state.entrainment_screw, +1),
                "nominal diameter (Fig 8)", time_s)

    values, state, time_s = results["ball_radius"]
    count_check("steps against: U falls, S rises with ball diameter",
                _steps_against(state.entrainment_nut, -1) + _steps_against(state.entrainment_screw, -1)
                + _steps_against(state.slide_roll_nut, +1) + _steps_against(state.slide_roll_screw, +1),
                "ball diameter (Fig 9)", time_s)
    run.check(model=MODEL, family="analytical", quantity="relative range of U_A over d_b 3-10 mm", unit="1",
              value=float(np.ptp(state.entrainment_nut) / np.mean(state.entrainment_nut)), reference=0.05,
              relation="le", tolerance=0.0, source=f"{source}: U 'reduces slightly' with ball diameter (Fig 9)",
              time_s=time_s, note="'slightly' read as below 5 %")
    leads = np.linspace(0.0, 40e-3, count)
    bearing = harris.kinematics(TABLE_A1["pitch_radius"], TABLE_A1["ball_radius"], TABLE_A1["screw_speed"],
                                TABLE_A1["contact_angle_nut"])
    run.save_figure(figures.methods_figure(leads, sk.kinematics(**{**TABLE_A1, "lead": leads}),
                                           sk.wei_ball_centre_kinematics(**{**TABLE_A1, "lead": leads}), bearing),
                    "methods_vs_lead.png")
    run.note("Sweep ranges are chosen here (the figures are missing from the text): speed 100-5000 rpm, "
             "alpha 30-60 deg, lead 2-40 mm, d_m 24-100 mm, d_b 3-10 mm, all other inputs Table A1. Verbal "
             "bounds ('negligible', 'dramatically') are read as stated in each row's note.")
