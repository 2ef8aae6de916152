"""fem: elasticity patch tests, contact solver (complementarity, equilibrium, force/approach
duality, non-convergence, coarse mesh refusal), post-processing fits, linear solvers."""
from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from ballbench.fem import contact, hertz_case, linsolve, postprocess
from ballbench.fem.elasticity import PairMesh, lame, stiffness
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.meshes.assemblies import contact_pairs

E, NU = 2.1e11, 0.28
R = 5e-3


def _cube(order_points: int = 3) -> PairMesh:
    from skfem import MeshTet

    mesh = MeshTet.init_tensor(*(np.linspace(0, 1e-3, order_points),) * 3)
    return PairMesh(mesh.p.T.copy(), mesh.t.T.copy(), np.zeros(mesh.t.shape[1], dtype=int), {})


@pytest.mark.parametrize("order", [1, 2])
def test_patch_test_uniform_strain(order):
    """A linear displacement field on the boundary is reproduced exactly inside (P1 and P2)."""
    pair = _cube()
    K, basis = stiffness(pair, (E, NU), order=order)
    grad = np.array([[1e-4, 2e-5, 0.0], [0.0, -3e-5, 1e-5], [4e-6, 0.0, 2e-4]])
    x = basis.doflocs  # (3, ndof): location of each DOF
    exact = np.einsum("ij,jk->ik", grad, x)  # u_i at every DOF location
    dof_comp = np.zeros(K.shape[0], dtype=int)
    for c in range(3):
        dof_comp[basis.nodal_dofs[c]] = c
        if order == 2:
            dof_comp[basis.edge_dofs[c]] = c
    u_exact = exact[dof_comp, np.arange(K.shape[0])]
    boundary = basis.get_dofs().flatten()
    interior = np.setdiff1d(np.arange(K.shape[0]), boundary)
    assert interior.size > 0
    u = u_exact.copy()
    u[interior] = 0.0
    rhs = -(K @ u)[interior]
    u[interior] = sp.linalg.spsolve(K[interior][:, interior].tocsc(), rhs)
    assert np.max(np.abs(u - u_exact)) < 1e-12 * np.max(np.abs(u_exact))


def test_rigid_body_modes_are_stress_free():
    pair = _cube()
    K, basis = stiffness(pair, (E, NU))
    x = pair.points
    for mode in (np.array([1.0, 0, 0]) + 0 * x, np.cross([0.3, -0.2, 1.0], x)):
        u = np.zeros(K.shape[0])
        for c in range(3):
            u[basis.nodal_dofs[c]] = mode[:, c]
        assert np.max(np.abs(K @ u)) < 1e-9 * np.max(np.abs(K.data)) * np.max(np.abs(u))


def test_lame_bad_input():
    with pytest.raises(ValueError, match="poisson_ratio"):
        lame(E, 0.5)
    with pytest.raises(ValueError, match="youngs_modulus"):
        lame(-1.0, 0.3)


def test_inverse_block_methods_agree():
    rng = np.random.default_rng(0)
    a = sp.random(400, 400, density=0.02, random_state=1)
    K = (a @ a.T + 3 * sp.eye(400)).tocsr()
    c = rng.choice(400, 12, replace=False)
    reference = np.linalg.inv(K.toarray())[np.ix_(c, c)]
    for method in linsolve.METHODS:
        assert np.allclose(linsolve.inverse_block(K, c, method), reference, rtol=1e-10, atol=1e-14)
    with pytest.raises(ValueError, match="method"):
        linsolve.inverse_block(K, c, "cg")
    # W = B K^-1 B^T: the augmented-system Schur complement agrees with the dense reference
    B = sp.random(15, 400, density=0.03, random_state=2).tocsr()
    W_ref = B @ np.linalg.inv(K.toarray()) @ B.T.toarray()
    for method in ("augmented", "schur", "rhs", "splu"):
        assert np.allclose(linsolve.compliance(K, B, method), W_ref, rtol=1e-10, atol=1e-14 * np.abs(W_ref).max())


def test_approach_fit_recovers_coefficients():
    forces = np.array([50.0, 75.0, 100.0, 125.0, 150.0])
    fit = postprocess.approach_fit(forces, 2e-7 * forces ** (2 / 3) - 1e-9 * forces)
    assert fit.hertz_constant == pytest.approx(2e-7, rel=1e-12)
    assert fit.bulk_compliance == pytest.approx(-1e-9, rel=1e-10)
    with pytest.raises(ValueError, match=">= 3"):
        postprocess.approach_fit([1.0, 2.0], [1.0, 2.0])


def test_mesh_check_gives_size():
    with pytest.raises(ValueError, match=r"use h_contact <= 2\.000e-05"):
        postprocess.mesh_check(5e-5, 1e-4)
    postprocess.mesh_check(1e-5, 1e-4)


@pytest.fixture(scope="module")
def flat_model():
    geometry = hertz.ball_on_flat(R, youngs_modulus=E, poisson_ratio=NU)
    ref = hertz.solve_load(geometry, 100.0)
    path = contact_pairs.ball_on_flat_pair(R, ref.a / 6, 1.4, fine_radius=1.3 * ref.a)
    return contact.build_model(path, (E, NU), gap_limit=1.25 * ref.delta), ref


def test_contact_complementarity_and_equilibrium(flat_model):
    model, ref = flat_model
    state = contact.solve_force(model, 100.0)
    scale = np.max(state.forces)
    assert state.force == pytest.approx(100.0, rel=1e-12)
    assert np.all(state.forces >= -1e-12 * scale)
    assert np.all(state.gaps >= -1e-10 * state.approach)
    assert np.max(np.abs(state.forces * state.gaps)) < 1e-10 * scale * state.approach
    assert state.residual <= 1e-10 and 2 <= state.iterations <= 50
    # the approach control gives back the same solution
    again = contact.solve_approach(model, state.approach)
    assert again.force == pytest.approx(100.0, rel=1e-9)
    assert np.allclose(again.forces, state.forces, atol=1e-9 * scale)
    # W is symmetric positive definite (a compliance)
    assert np.allclose(model.W, model.W.T)
    assert np.min(np.linalg.eigvalsh(model.W)) > 0


def test_contact_is_monotone_and_hertz_like(flat_model):
    model, ref = flat_model
    low, high = contact.solve_force(model, 50.0), contact.solve_force(model, 100.0)
    assert high.approach > low.approach and high.active.sum() >= low.active.sum()
    # Hertz: U(100)/U(50) = 2^(2/3) up to the (small) linear bulk term
    assert high.approach / low.approach == pytest.approx(2 ** (2 / 3), rel=0.05)


def test_nonconvergence_raises(flat_model):
    model, _ = flat_model
    with pytest.raises(ConvergenceError, match="residual"):
        contact.solve_force(model, 100.0, max_iter=1)


def test_bad_loads(flat_model):
    model, _ = flat_model
    for bad in (0.0, -5.0, float("nan")):
        with pytest.raises(ValueError, match="force"):
            contact.solve_force(model, bad)
    with pytest.raises(ValueError, match="approach"):
        contact.solve_approach(model, -1e-6)


def test_contact_zone_too_small_is_refused(flat_model):
    model, ref = flat_model
    with pytest.raises(ValueError, match="edge of the candidate zone"):
        contact.solve_force(model, 800.0)


def test_too_coarse_mesh_is_refused():
    geometry = hertz.ball_in_groove(R, 0.56, youngs_modulus=E, poisson_ratio=NU)
    ref = hertz.solve_load(geometry, 100.0)
    with pytest.raises(ValueError, match="mesh too coarse.*use h_contact <="):
        hertz_case.solve_case(lambda: contact_pairs.ball_in_groove_pair(R, 0.56, ref.b / 2.5, 1.5,
                                                                        fine_radius=1.4 * ref.b,
                                                                        fine_half_length=1.1 * ref.a),
                              100.0, (E, NU), gap_limit=1.25 * ref.delta)


def test_ellipse_fit_recovers_exact_hertz_forces(flat_model):
    model, ref = flat_model
    xq, operator = postprocess.force_operator(model.pair.points, model.pair.surfaces["ball_contact"],
                                              model.candidates)
    a, b, p0 = 1.1 * ref.a, 0.8 * ref.a, 2e9
    field = p0 * np.sqrt(np.clip(1 - (xq[:, 0] / a) ** 2 - (xq[:, 1] / b) ** 2, 0, None))
    fit = postprocess.fit_ellipse_forces(xq, operator, operator @ field)
    assert (fit.a, fit.b, fit.p0) == pytest.approx((a, b, p0), rel=1e-8)
    # a quarter model: the fitted field is the whole ellipse, its force the full one without a symmetry factor,
    # 4x the quarter's nodal forces (to the quadrature's 4e-5); scaling it by the factor would give 4x too much
    assert model.symmetry_factor == 4
    assert fit.force == pytest.approx(2 * np.pi * p0 * a * b / 3, rel=1e-8)
    assert fit.force == pytest.approx(model.symmetry_factor * (operator @ field).sum(), rel=1e-3)


def test_groove_quick_level_against_hertz():
    """Coarse CI level of the conformity-0.56 groove: within 3 % (p0 4 %) of Hertz."""
    from ballbench.validation.cases import lin2019
    from ballbench.validation.studies import fe_contact

    case = lin2019.CONTACT_GROOVE_056
    level, = case.fe.levels["quick"]
    result, ref = fe_contact.solve_level(fe_contact.pair_model(case), level)
    assert result.force_sum == pytest.approx(100.0, rel=1e-12)
    for quantity, tol in {"a": 0.03, "b": 0.03, "p0": 0.04, "delta": 0.03}.items():  # the scene's quick tolerances
        assert getattr(result, quantity) == pytest.approx(float(getattr(ref, quantity)), rel=tol), quantity


@pytest.fixture(scope="module", params=[1, 2], ids=["P1", "P2"])
def mortar_flat(request):
    from ballbench.fem.mortar import build_mortar_model

    geometry = hertz.ball_on_flat(R, youngs_modulus=E, poisson_ratio=NU)
    ref = hertz.solve_load(geometry, 100.0)
    path = contact_pairs.ball_on_flat_pair(R, ref.a / 5, 1.5, fine_radius=1.3 * ref.a)
    model = build_mortar_model(path, (E, NU), 1.25 * ref.delta, order=request.param,
                               initial_gap=lambda x, y: geometry.A * x * x + geometry.B * y * y)
    return model, ref


def test_mortar_complementarity_and_equilibrium(mortar_flat):
    model, ref = mortar_flat
    assert model.multiplier == "pressure"
    # the weights m_i = int phi_i dA add up to the projected area of the candidate zone
    assert np.all(model.weights > 0)
    state = contact.solve_force(model, 100.0)
    assert state.force == pytest.approx(100.0, rel=1e-12)
    assert np.all(state.pressure >= -1e-9 * np.max(state.pressure))
    assert np.all(state.gaps >= -1e-10 * state.approach * np.max(model.weights))
    assert state.residual <= 1e-10
    again = contact.solve_approach(model, state.approach)
    assert np.allclose(again.pressure, state.pressure, atol=1e-8 * np.max(state.pressure))


def test_p2_mortar_flat_against_hertz():
    """P2 mortar on a coarse quarter ball-on-flat: a, p0, delta within 1.5 % of Hertz."""
    geometry = hertz.ball_on_flat(R, youngs_modulus=E, poisson_ratio=NU)
    ref = hertz.solve_load(geometry, 100.0)
    result = hertz_case.solve_case(
        lambda: contact_pairs.ball_on_flat_pair(R, ref.a / 5.5, 1.5, fine_radius=1.3 * ref.a), 100.0, (E, NU),
        gap_limit=1.25 * ref.delta, initial_gap=lambda x, y: geometry.A * x * x + geometry.B * y * y,
        formulation="mortar", order=2)
    assert result.a == pytest.approx(ref.a, rel=0.015)
    assert result.b == pytest.approx(ref.b, rel=0.015)
    assert result.p0 == pytest.approx(ref.p0, rel=0.015)
    assert result.delta == pytest.approx(ref.delta, rel=0.015)


def test_bad_formulation():
    with pytest.raises(ValueError, match="formulation"):
        hertz_case.solve_case(lambda: contact_pairs.ball_on_flat_pair(R, 2.5e-4, 1.5), 100.0, (E, NU),
                              gap_limit=1e-6, formulation="penalty")


@pytest.mark.parametrize("order", [1, 2])
def test_fast_assembly_equals_scikit_fem(order):
    from ballbench.fem.elasticity import load_pair, stiffness_fast

    pair = load_pair(contact_pairs.ball_on_flat_pair(R, 2.5e-4, 1.5))
    materials = [(E, NU), (2.0e11, 0.3)]
    K_ref, _ = stiffness(pair, materials, order=order)
    K_fast, _ = stiffness_fast(pair, materials, order=order, chunk=3000)
    assert abs(K_ref - K_fast).max() < 1e-12 * abs(K_ref).max()


def test_kept_factor_solves_with_the_same_matrix():
    """compliance(..., keep_factor=True): W unchanged, and the kept factor of [[K, B^T], [B, 0]] solves
    u = K^-1 (f - B^T mu) by partial solves.  Catches a factor whose Schur unknowns are not set to mu
    (or are left at the forward-solve values), or partial solves in the wrong order: u differs at O(1)."""
    a = sp.random(400, 400, density=0.02, random_state=1)
    K = (a @ a.T + 3 * sp.eye(400)).tocsr()
    B = sp.random(15, 400, density=0.03, random_state=2).tocsr()
    dense = np.linalg.inv(K.toarray())
    W, factor = linsolve.compliance(K, B, keep_factor=True)
    assert np.allclose(W, B @ dense @ B.T.toarray(), rtol=1e-10, atol=1e-14 * np.abs(W).max())
    rng = np.random.default_rng(3)
    f, mu = rng.standard_normal(400), rng.standard_normal(15)
    for u, reference in ((factor.solve(f, mu), dense @ (f - B.T @ mu)), (factor(f), dense @ f)):
        assert np.max(np.abs(u - reference)) < 1e-10 * np.max(np.abs(reference))
    with pytest.raises(ValueError, match="shape"):
        factor.solve(f[:-1])
    factor.free()
    factor.free()  # idempotent
    with pytest.raises(RuntimeError, match="freed"):
        factor.solve(f)
    assert linsolve.compliance(K, B, "schur", keep_factor=True)[1] is None  # no extra factorisation


def test_full_solution_reuses_the_condensation_factor(mortar_flat, monkeypatch):
    """The VTU's full displacement field needs no second factorisation of K (docs/fem.md, kept factor) and equals
    the one of a fresh factorisation; with the factor freed it factorises once more."""
    model, ref = mortar_flat
    state = contact.solve_force(model, 100.0)
    calls = []
    original = linsolve.factorize

    def counting(K):
        calls.append(K.shape)
        return original(K)

    monkeypatch.setattr(linsolve, "factorize", counting)
    kept = contact.full_solution(model, state)
    assert calls == []
    fresh = contact.solve_free(model.K, model.free, (model.B.T @ state.pressure - model.K @ _loaded(model, state))[
        model.free], None)
    assert calls == [(model.free.size, model.free.size)]
    u = _loaded(model, state)
    u[model.free] = fresh
    assert np.max(np.abs(kept - u)) < 1e-9 * np.max(np.abs(u))


def _loaded(model, state):
    u = np.zeros(model.K.shape[0])
    u[model.load_dofs] = -state.approach
    return u


def test_hookes_law_and_von_mises():
    """fem.elasticity.stress and von_mises on closed forms: uniaxial stress (strain (s, -nu s, -nu s)/E gives
    sigma = diag(s, 0, 0), von Mises |s|), pure shear (von Mises sqrt(3) tau) and a rotation (no stress).  Catches
    lambda and mu swapped, a missing symmetrisation or a deviator without the mean stress."""
    from ballbench.fem.elasticity import lame, stress, von_mises

    lam, mu = lame(E, NU)
    s = 3.0e8
    uniaxial = np.diag([s, -NU * s, -NU * s]) / E
    np.testing.assert_allclose(stress(uniaxial, lam, mu), np.diag([s, 0.0, 0.0]), atol=1e-6 * s)
    assert von_mises(stress(uniaxial, lam, mu)) == pytest.approx(s, rel=1e-12)
    tau = 1.0e8
    shear = np.zeros((3, 3))
    shear[0, 1] = tau / mu  # du_x/dy: engineering shear strain tau / G
    sigma = stress(shear, lam, mu)
    assert sigma[0, 1] == pytest.approx(tau, rel=1e-12) and sigma[1, 0] == pytest.approx(tau, rel=1e-12)
    assert von_mises(sigma) == pytest.approx(np.sqrt(3.0) * tau, rel=1e-12)
    rotation = np.array([[0.0, -1e-3, 0.0], [1e-3, 0.0, 0.0], [0.0, 0.0, 0.0]])
    np.testing.assert_array_equal(stress(rotation, lam, mu), np.zeros((3, 3)))
    # arrays of gradients (3, 3, e, q) broadcast with per-element Lame parameters
    grads = np.repeat(uniaxial[:, :, None, None], 2, axis=2).repeat(3, axis=3)
    np.testing.assert_allclose(von_mises(stress(grads, np.full((2, 3), lam), np.full((2, 3), mu))), s, rtol=1e-12)


def test_a_contact_pair_without_a_named_surface_is_refused():
    import dataclasses

    from ballbench.fem import elasticity
    from ballbench.meshes.assemblies import contact_pairs

    path = contact_pairs.ball_on_flat_pair(10e-3, 4e-4, 1.6)
    pair = elasticity.contact_pair(path)  # the mesh of meshes.assemblies has every surface a contact solve needs
    assert {"ball_contact", "counter_contact", "ball_load", "counter_support"} <= set(pair.surfaces)
    surfaces = {name: faces for name, faces in pair.surfaces.items() if name != "counter_support"}
    with pytest.raises(ValueError, match="'counter_support' missing"):
        elasticity.contact_pair(dataclasses.replace(pair, surfaces=surfaces))
