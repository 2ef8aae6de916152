"""Regenerate the small saved fields of tests/test_render3d.py (run from the repository root):

    .venv/bin/python tests/data/render3d/regenerate.py

Solves three coarse cases (about 30 s) and writes them as the scenes do, then shrinks them for the repository:
the corner nodes of the quadratic tetrahedra only (linear tetrahedra, which render3d reads as well) and float32
data.  A coarse mesh is enough: the tests judge the pictures, not the FE.

* ``pair/``: the ball on a flat (fe-hertz-flat) at n = b/h 5, growth 2, 100 N (validation.studies.fe_contact);
* ``module/``: lin2019's two-ball linear module, case (a), at h 90 um, growth 2 (validation.studies.fe_b2b_linear);
* ``surface/``: the sun2021 dry BEM at A, 21.71 deg, 32 x 32 cells (validation.studies.sun2021);
* ``stickslip/``: steady rolling of a Hertz ellipse (a/b 0.5, 24 x 24 cells) at a creepage with a large stick area
  and with creepage and spin (lowmodel.contact.rolling; :func:`stickslip`, a second alone).

After regenerating, reset the baseline images: ``BALLBENCH_RESET_BASELINES=1 .venv/bin/python -m pytest
tests/test_render3d.py`` and look at them (tests/baseline_images/render3d/).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def shrink(path: Path) -> None:
    """Rewrite the VTU ``path`` with linear tetrahedra (the corner nodes) and float32 data."""
    import meshio

    mesh = meshio.read(path)
    cells = mesh.cells_dict["tetra10"][:, :4]
    used, local = np.unique(cells, return_inverse=True)
    point_data = {k: np.asarray(v)[used].astype(np.float32) for k, v in mesh.point_data.items()
                  if k != "sigma_zz_Pa"}
    cell_data = {k: [np.asarray(v["tetra10"]).astype(np.int32 if k == "body" else np.float32)]
                 for k, v in mesh.cell_data_dict.items()}
    meshio.Mesh(mesh.points[used].astype(np.float32), [("tetra", local.reshape(-1, 4))], point_data=point_data,
                cell_data=cell_data).write(path, compression="zlib")


def main() -> None:
    from ballbench.fem.fields import write_module_fields, write_surface_fields
    from ballbench.validation.cases import lin2019
    from ballbench.validation.cases.case import ModuleLevel, PairLevel
    from ballbench.validation.studies import fe_b2b_linear, fe_contact, sun2021

    case = lin2019.CONTACT_FLAT
    level = PairLevel(5.0, 2.0)
    result, ref = fe_contact.solve_level(fe_contact.pair_model(case), level)
    fe_contact.write_fields(result, ref, HERE / "pair", scene_name="fe-hertz-flat", fidelity="test", level=level,
                            material=case.material)
    shrink(HERE / "pair" / "fields.vtu")

    guide = lin2019.TABLE3_A
    model, results, _ = fe_b2b_linear.solve_fe_level(guide, ModuleLevel(9e-5, 2.0, None))
    paths = write_module_fields(HERE / "module", model, results, materials=guide.guide.material.pair,
                                scene="fe-b2b-linear-a", fidelity="test", level={"h_contact_m": 9e-5, "growth": 2.0},
                                case="theta 2 deg, rho -0.6")
    for path in paths[:-1]:
        shrink(path)

    contact = sun2021.dry_contact(21.71, "A", 32)
    bem = contact.bem
    write_surface_fields(HERE / "surface", "bem_A", bem.grid.x, bem.grid.y,
                         {"pressure_Pa": bem.pressure, "separation_m": bem.separation},
                         {"scene": "sun2021-dry-contact", "fidelity": "test", "title": "dry BEM at A, 32 x 32",
                          "axes": ["major axis", "minor axis"]})
    stickslip()


def stickslip() -> None:
    """The two rolling contacts of ``stickslip/`` (validation.figures.stickslip3d.write_fields)."""
    from ballbench.lowmodel.contact import rolling
    from ballbench.validation.figures import stickslip3d

    a, b, force, shear, nu, mu = 0.5e-3, 1e-3, 500.0, 80e9, 0.28, 0.3
    p0 = 1.5 * force / (np.pi * a * b)
    scale = mu * p0 / shear
    contacts = [("creepage", rolling.steady_rolling(a, b, force, shear, nu, mu, 0.5 * scale, 0.0, 0.0, (24, 24))),
                ("creepage and spin", rolling.steady_rolling(a, b, force, shear, nu, mu, 0.3 * scale, 0.0,
                                                             1.5 * scale / b, (24, 24)))]
    (HERE / "stickslip").mkdir(exist_ok=True)
    stickslip3d.write_fields(HERE / "stickslip", "rolling", contacts, scene="rolling-test", fidelity="test",
                             title="a Hertz ellipse rolling, 24 x 24 cells", ellipses=[(a, b)] * 2)


if __name__ == "__main__":
    main()
