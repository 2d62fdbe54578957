//! `init`: consistent initial accelerations (and multipliers) for the structural
//! integrators, computed from `q_0`, `v_0` at `t_0`.
//!
//! Unconstrained systems (every method's `init` but the index-3 one):
//!
//! ```text
//! (I1)  M(q_0) a_0 = -f(t_0, q_0, v_0),       M = dr/da,  f = r(t_0, q_0, v_0, 0).
//! ```
//!
//! A singular `M` (massless coordinates, e.g. rotational degrees of freedom without inertia
//! or an intermediate node of a spring chain) leaves (I1) without a unique solution: row `i`
//! of a zero row of `M` is the algebraic equation `f_i(t, q, v) = 0`, which fixes the
//! coordinate, not its acceleration. Each zero row (`max_j |M_ij| <= eps max|M|`) is then
//! replaced by the row of the twice-differentiated constraint, kept to its stiffness part:
//!
//! ```text
//! (I2)  sum_j (df_i/dq_j) a_0j = 0          (K = dr/dq, the tangent with c_k = 1 only),
//! ```
//!
//! exact when `f_i` is linear in `q` and depends on neither `v` nor `t` (elastic springs on a
//! massless node); otherwise `a_0` of the massless coordinates is an `O(1)` guess, its error
//! a transient the dissipative methods (HHT, generalized-alpha) damp and Newmark keeps (its
//! spectral radius at infinity is 1). The massless positions do not depend on it: their
//! equations hold at every step. When the combined matrix is singular too (a massless
//! coordinate without stiffness), `init` fails; a caller can still write a known `a_0` into
//! `State::a` and `State::aux` and step without calling `init`.
//!
//! Constrained systems (index-3 generalized-alpha): `a_0` and `lambda_0` satisfy the
//! equations of motion and the twice-differentiated constraint,
//!
//! ```text
//! (I3)  [ M  G^T ] [ a_0      ]   [ -f                                   ]
//!       [ G  0   ] [ lambda_0 ] = [ -(dG/dq v) v - 2 (dg_t/dq) v - g_tt  ],
//! ```
//!
//! with the curvature terms `(dG/dq v) v` and `(dg_t/dq) v` by central differences along `v`
//! (step `eps^(1/3) (1 + |q|_inf) / |v|_inf`, error about `1e-10` relative). Consistent
//! starting values matter: Arnold & Brüls (2007) show that the multipliers and
//! accelerations of the index-3 scheme converge with order 2 only from consistent (and, for
//! the full order, perturbed) starting values. Fails when the saddle-point matrix is
//! singular (redundant constraints, or massless directions the constraints do not fix).
use super::newton::lu_failure;
use super::state::State;
use super::{Constraints, SecondOrder};
use crate::integrate::{Failure, Stats};
use crate::math::lu::LinearSolve;

/// Solves (I1) (with (I2) for massless rows) and writes `a_0` into `state.a` and
/// `state.aux`. One residual evaluation. `method` names the caller in failures.
pub(crate) fn acceleration<S: SecondOrder + ?Sized>(
    sys: &S,
    t0: f64,
    state: &mut State,
    stats: &mut Stats,
    method: &str,
) -> Result<(), Failure> {
    let n = sys.dim();
    state.assert_sizes(n, state.n_constraints());
    let w = &mut state.work;
    w.a1.fill(0.0);
    sys.residual(t0, &state.q, &state.v, &w.a1, &mut w.r);
    stats.rhs_evals += 1;
    super::newton::check_finite(&w.r, t0, method, "initial force")?;
    sys.tangent(
        t0,
        &state.q,
        &state.v,
        &w.a1,
        1.0,
        0.0,
        0.0,
        w.lu_n.matrix_mut(),
    );
    let m = w.lu_n.matrix_mut();
    let mmax = m.amax();
    let massless = |m: &nalgebra::DMatrix<f64>, i: usize| {
        (0..n).all(|j| m[(i, j)].abs() <= f64::EPSILON * mmax)
    };
    if (0..n).any(|i| massless(m, i)) {
        sys.tangent(t0, &state.q, &state.v, &w.a1, 0.0, 0.0, 1.0, &mut w.s);
        let m = w.lu_n.matrix_mut();
        for i in 0..n {
            if massless(m, i) {
                for j in 0..n {
                    m[(i, j)] = w.s[(i, j)];
                }
                w.r[i] = 0.0;
            }
        }
    }
    w.lu_n.factor().map_err(|e| {
        let mut f = lu_failure(e, t0, method);
        f.message = format!(
            "{}: initial acceleration: mass matrix (massless rows replaced by their \
             stiffness rows) is singular; set State::a and State::aux yourself",
            f.message
        );
        f
    })?;
    w.r.neg_mut();
    w.lu_n
        .solve_in_place(&mut w.r)
        .map_err(|e| lu_failure(e, t0, method))?;
    state.a.copy_from(&w.r);
    state.aux.copy_from(&w.r);
    Ok(())
}

/// Solves (I3) and writes `a_0` into `state.a`, `state.aux` and `lambda_0` into
/// `state.lambda`. One residual evaluation.
pub(crate) fn acceleration_constrained<S: Constraints + ?Sized>(
    sys: &S,
    t0: f64,
    state: &mut State,
    stats: &mut Stats,
    method: &str,
) -> Result<(), Failure> {
    let (n, m) = (sys.dim(), sys.n_constraints());
    state.assert_sizes(n, m);
    let (q, v) = (&state.q, &state.v);
    let w = &mut state.work;
    w.a1.fill(0.0);
    sys.residual(t0, q, v, &w.a1, &mut w.r);
    stats.rhs_evals += 1;
    super::newton::check_finite(&w.r, t0, method, "initial force")?;
    sys.tangent(t0, q, v, &w.a1, 1.0, 0.0, 0.0, &mut w.s);
    sys.jacobian(t0, q, &mut w.jac);
    // Curvature terms along v by central differences: w.g collects the right-hand side.
    sys.g_time(t0, q, &mut w.gt_p, &mut w.gtt);
    w.g.copy_from(&w.gtt);
    let vmax = v.amax();
    if vmax > 0.0 && m > 0 {
        let eps = f64::EPSILON.cbrt() * (1.0 + q.amax()) / vmax;
        // + side
        w.qt.copy_from(q);
        w.qt.axpy(eps, v, 1.0);
        sys.jacobian(t0, &w.qt, &mut w.jac_t);
        w.g.gemv(0.5 / eps, &w.jac_t, v, 1.0);
        sys.g_time(t0, &w.qt, &mut w.gt_p, &mut w.lambda1);
        // - side
        w.qt.copy_from(q);
        w.qt.axpy(-eps, v, 1.0);
        sys.jacobian(t0, &w.qt, &mut w.jac_t);
        w.g.gemv(-0.5 / eps, &w.jac_t, v, 1.0);
        sys.g_time(t0, &w.qt, &mut w.gt_m, &mut w.lambda1);
        // 2 (dg_t/dq) v = 2 (g_t(q + eps v) - g_t(q - eps v)) / (2 eps)
        w.g.axpy(1.0 / eps, &w.gt_p, 1.0);
        w.g.axpy(-1.0 / eps, &w.gt_m, 1.0);
    }
    let big = w.lu_c.matrix_mut();
    big.fill(0.0);
    big.view_mut((0, 0), (n, n)).copy_from(&w.s);
    big.view_mut((n, 0), (m, n)).copy_from(&w.jac);
    big.view_mut((0, n), (n, m)).tr_copy_from(&w.jac);
    w.lu_c.factor().map_err(|e| {
        let mut f = lu_failure(e, t0, method);
        f.message = format!(
            "{}: initial acceleration: the matrix [M G^T; G 0] is singular (redundant \
             constraints, or massless directions they do not fix)",
            f.message
        );
        f
    })?;
    for i in 0..n {
        w.rhs[i] = -w.r[i];
    }
    for k in 0..m {
        w.rhs[n + k] = -w.g[k];
    }
    w.lu_c
        .solve_in_place(&mut w.rhs)
        .map_err(|e| lu_failure(e, t0, method))?;
    for i in 0..n {
        state.a[i] = w.rhs[i];
    }
    state.aux.copy_from(&state.a);
    for k in 0..m {
        state.lambda[k] = w.rhs[n + k];
    }
    Ok(())
}
