//! A beam model in residual form (`Beamlike`, `structural::SecondOrder`) as a first-order ODE
//! for the rigid core's generic integrators (`rk4`, `dopri5`, `dop853`, `implicit_midpoint`,
//! `gauss6`), which need a `Copy` state: [`AsOde<S, D>`] holds it in an `SVector<f64, D>` with
//! `D = 2 n + 2` for a model of `n` coordinates (`x = [q; v; w; t]`: coordinates, rates, the
//! drive's work integral `int H Om' dt` (`observe.rs`) and the time, which the observation of
//! a moving base needs and every consistent method integrates exactly). Each registered
//! model size is one monomorphised type (`family.rs` lists them).
//!
//! The rates solve `M(q) a = -f(t, q, v)` (the residual at `a = 0`, the mass matrix as the
//! tangent with `c_m = 1`, `c_c = c_k = 0`, one dense LU per evaluation). A free hub's rate
//! is replaced by its angular momentum `H = (M(q) v)_0` (the hub angle is cyclic): then
//! `H' = tau(t)`, a linear invariant that every Runge-Kutta method conserves to round-off
//! (after the torque ends `H` stays at `tau t_off` exactly, Noether's law held by the
//! discretisation); the hub rate is recovered from `H` and the other rates. The mass matrix
//! is factored once per run: on a prescribed base it is constant, and a free hub's changes
//! only in the hub's row and column, which a Schur complement on the constant rest absorbs
//! (`accelerations`). The scratch buffers sit behind a mutex (one per run, uncontended), so an
//! evaluation allocates nothing.
//!
//! Where it fails: a singular mass matrix (a massless coordinate) makes every evaluation a
//! `non_finite` failure; the axial modes' frequencies bound the explicit methods' steps.
use nalgebra::{DMatrix, DVector, SVector};
use std::sync::Mutex;

use super::base::Base;
use super::observe::{BeamObs, Beamlike, observe};
use super::run::check_bound;
use crate::integrate::{Failure, FailureKind, Limits, Stats, System};
use crate::math::lu::{DenseLu as Lu, LinearSolve};
use crate::methods::OdeMethod;
use crate::run::{Grid, Observe, RunOutput, Sample, Stepping};

struct Scratch {
    q: DVector<f64>,
    v: DVector<f64>,
    a: DVector<f64>,
    r: DVector<f64>,
    m: DMatrix<f64>,
    lu: Lu,
    /// The augmented system `[M C^T; C 0]` and its right side (constrained forms only).
    aug: Lu,
    rhs: DVector<f64>,
    /// A free hub: the constant system without the hub's row and column,
    /// `K = [M_rr C_r^T; C_r 0]`, factored once, and two solution buffers.
    rest: Lu,
    y: DVector<f64>,
    z: DVector<f64>,
    /// A free hub's mass column (`Beamlike::hub_column`).
    col: DVector<f64>,
}

/// How a constrained form keeps its linear constraints `C q = 0` (`C` is `m x n`, with a zero
/// column for a free hub's angle): the accelerations solve
/// `[M C^T; C 0] [a; lambda] = [-f; -2 alpha C v - beta^2 C q]` (Baumgarte's stabilised
/// index-1 form, `g'' + 2 alpha g' + beta^2 g = 0`, stable for `alpha, beta > 0`; plain index 1
/// with `alpha = beta = 0`), and with `project` every step ends with the `M`-orthogonal
/// projections `q <- q - M^-1 C^T (C M^-1 C^T)^-1 C q` and likewise `v` (they leave a free
/// hub's `H = (M v)_0` unchanged, as `C` has no hub column).
#[derive(Debug, Clone, PartialEq)]
pub struct Stabilised {
    pub rows: DMatrix<f64>,
    pub alpha: f64,
    pub beta: f64,
    pub project: bool,
}

/// A beam model as an ODE on `x = [q; v; w; t]` (module docs).
pub struct AsOde<S: Beamlike, const D: usize> {
    pub sys: S,
    n: usize,
    cyclic: bool,
    /// The mass matrix does not depend on the state or time (a prescribed base): factored
    /// once at construction.
    constant: bool,
    bound: f64,
    stab: Option<Stabilised>,
    scratch: Mutex<Scratch>,
}

impl<S: Beamlike, const D: usize> AsOde<S, D> {
    /// The ODE of `sys`, whose runs end as `diverged` when `|v_tip| > bound`.
    pub fn new(sys: S, bound: f64) -> Result<Self, String> {
        Self::constrained(sys, bound, None)
    }

    /// The ODE of `sys` with its constraints kept by `stab` (None: unconstrained).
    pub fn constrained(sys: S, bound: f64, stab: Option<Stabilised>) -> Result<Self, String> {
        let n = sys.dim();
        let m = stab.as_ref().map_or(0, |s| s.rows.nrows());
        if let Some(st) = &stab
            && (st.rows.ncols() != n || m >= n)
        {
            return Err(format!(
                "{m} constraint rows of {} columns on a model of {n} coordinates",
                st.rows.ncols()
            ));
        }
        if D != 2 * n + 2 {
            return Err(format!(
                "a model of {n} coordinates needs a state of {} numbers, not {D}",
                2 * n + 2
            ));
        }
        let cyclic = matches!(sys.base(), Base::Free { .. });
        let constant = sys.constant_mass();
        let ode = AsOde {
            sys,
            n,
            cyclic,
            constant,
            bound,
            stab,
            scratch: Mutex::new(Scratch {
                q: DVector::zeros(n),
                v: DVector::zeros(n),
                a: DVector::zeros(n),
                r: DVector::zeros(n),
                m: DMatrix::zeros(n, n),
                lu: Lu::new(n),
                aug: Lu::new(n + m),
                rhs: DVector::zeros(n + m),
                rest: Lu::new(if cyclic { n - 1 + m } else { 0 }),
                y: DVector::zeros(if cyclic { n - 1 + m } else { 0 }),
                z: DVector::zeros(if cyclic { n - 1 + m } else { 0 }),
                col: DVector::zeros(n),
            }),
        };
        if cyclic {
            // Everything but the hub's row and column is constant: factored once, here.
            let mut s = ode.lock();
            let Scratch {
                q, v, a, m, rest, ..
            } = &mut *s;
            ode.sys.tangent(0.0, q, v, a, 1.0, 0.0, 0.0, m);
            let k = rest.matrix_mut();
            k.fill(0.0);
            k.view_mut((0, 0), (n - 1, n - 1))
                .copy_from(&m.view((1, 1), (n - 1, n - 1)));
            if let Some(st) = &ode.stab {
                for i in 0..m_rows(st) {
                    for j in 1..n {
                        k[(n - 1 + i, j - 1)] = st.rows[(i, j)];
                        k[(j - 1, n - 1 + i)] = st.rows[(i, j)];
                    }
                }
            }
            if rest.factor().is_err() {
                return Err("the mass matrix without the hub is singular".into());
            }
        }
        if constant {
            // The mass (and constraint) matrix is factored once, here.
            let mut s = ode.lock();
            let Scratch {
                q,
                v,
                a,
                m,
                lu,
                aug,
                ..
            } = &mut *s;
            ode.sys.tangent(0.0, q, v, a, 1.0, 0.0, 0.0, m);
            if !ode.factor(m, lu, aug) {
                return Err("the mass matrix is singular".into());
            }
        }
        Ok(ode)
    }

    /// The state of `(q, v)` at `t = 0` with work integral 0.
    pub fn state(&self, q: &DVector<f64>, v: &DVector<f64>) -> SVector<f64, D> {
        let n = self.n;
        let mut x = SVector::<f64, D>::zeros();
        for i in 0..n {
            x[i] = q[i];
            x[n + i] = v[i];
        }
        if self.cyclic {
            let mut s = self.lock();
            s.a.fill(0.0);
            let Scratch {
                q: sq, v: sv, a, m, ..
            } = &mut *s;
            sq.copy_from(q);
            sv.copy_from(v);
            self.sys.tangent(0.0, sq, sv, a, 1.0, 0.0, 0.0, m);
            x[n] = (0..n).map(|j| m[(0, j)] * v[j]).sum();
        }
        x
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Scratch> {
        self.scratch.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Unpacks `x` into the scratch's `q`, `v` (recovering a free hub's rate from `H`) and
    /// forms `M(q)` in `m`.
    fn unpack(&self, s: &mut Scratch, x: &SVector<f64, D>) {
        let n = self.n;
        let t = x[2 * n + 1];
        for i in 0..n {
            s.q[i] = x[i];
            s.v[i] = x[n + i];
        }
        s.a.fill(0.0);
        let Scratch {
            q, v, a, m, col, ..
        } = s;
        if self.cyclic && self.sys.hub_column(q, col) {
            // Only the hub's row and column change (the rest was formed at construction).
            for j in 0..self.n {
                m[(0, j)] = col[j];
                m[(j, 0)] = col[j];
            }
        } else if !self.constant {
            self.sys.tangent(t, q, v, a, 1.0, 0.0, 0.0, m);
        }
        if self.cyclic {
            let rest: f64 = (1..n).map(|j| m[(0, j)] * v[j]).sum();
            v[0] = (x[n] - rest) / m[(0, 0)];
        }
    }

    /// Overwrites `s.r` (holding `-f`) with the accelerations: `M a = -f`, or the augmented
    /// system of a constrained form (Baumgarte's right side `-2 alpha C v - beta^2 C q`).
    /// A free hub solves by its Schur complement on the constant rest `K` (two solves: `K y =
    /// [-f_r; c]`, `K z = [b; 0]` with `b` the hub's column; `a_0 = (-f_0 - b^T y) / (J - b^T
    /// z)`, `a_r = y - a_0 z`), so nothing is factored per evaluation; a prescribed base uses
    /// the factors made at construction. False when a solve fails.
    fn accelerations(&self, s: &mut Scratch) -> bool {
        let n = self.n;
        let k = self.stab.as_ref().map_or(0, m_rows);
        if let Some(st) = &self.stab {
            for i in 0..k {
                let (mut cv, mut cq) = (0.0, 0.0);
                for j in 0..n {
                    cv += st.rows[(i, j)] * s.v[j];
                    cq += st.rows[(i, j)] * s.q[j];
                }
                s.rhs[n + i] = -2.0 * st.alpha * cv - st.beta * st.beta * cq;
            }
        }
        if self.cyclic {
            for i in 1..n {
                s.y[i - 1] = s.r[i];
                s.z[i - 1] = s.m[(i, 0)];
            }
            for i in 0..k {
                s.y[n - 1 + i] = s.rhs[n + i];
                s.z[n - 1 + i] = 0.0;
            }
            if s.rest.solve_in_place(&mut s.y).is_err() || s.rest.solve_in_place(&mut s.z).is_err()
            {
                return false;
            }
            let (mut by, mut bz) = (0.0, 0.0);
            for i in 1..n {
                by += s.m[(i, 0)] * s.y[i - 1];
                bz += s.m[(i, 0)] * s.z[i - 1];
            }
            let a0 = (s.r[0] - by) / (s.m[(0, 0)] - bz);
            s.r[0] = a0;
            for i in 1..n {
                s.r[i] = s.y[i - 1] - a0 * s.z[i - 1];
            }
            return a0.is_finite();
        }
        if !self.constant && !self.factor(&s.m, &mut s.lu, &mut s.aug) {
            return false;
        }
        match &self.stab {
            None => s.lu.solve_in_place(&mut s.r).is_ok(),
            Some(_) => {
                s.rhs.rows_mut(0, n).copy_from(&s.r);
                let ok = s.aug.solve_in_place(&mut s.rhs).is_ok();
                s.r.copy_from(&s.rhs.rows(0, n));
                ok
            }
        }
    }

    /// Factors `M` into `lu`, or `[M C^T; C 0]` into `aug` for a constrained form; false when
    /// singular.
    fn factor(&self, m: &DMatrix<f64>, lu: &mut Lu, aug: &mut Lu) -> bool {
        let n = self.n;
        match &self.stab {
            None => lu.factor_from(m).is_ok(),
            Some(st) => {
                let am = aug.matrix_mut();
                am.fill(0.0);
                am.view_mut((0, 0), (n, n)).copy_from(m);
                for i in 0..st.rows.nrows() {
                    for j in 0..n {
                        am[(n + i, j)] = st.rows[(i, j)];
                        am[(j, n + i)] = st.rows[(i, j)];
                    }
                }
                aug.factor().is_ok()
            }
        }
    }

    /// The observation of a state.
    pub fn obs(&self, x: &SVector<f64, D>) -> BeamObs {
        let mut s = self.lock();
        self.unpack(&mut s, x);
        let n = self.n;
        observe(&self.sys, x[2 * n + 1], &s.q, &s.v, x[2 * n])
    }
}

/// The number of constraint rows.
fn m_rows(st: &Stabilised) -> usize {
    st.rows.nrows()
}

impl<S: Beamlike, const D: usize> System for AsOde<S, D> {
    type State = SVector<f64, D>;
    type Tangent = SVector<f64, D>;
    const LIE: bool = false;

    fn rhs(&self, _t: f64, x: &SVector<f64, D>) -> SVector<f64, D> {
        let n = self.n;
        let t = x[2 * n + 1];
        let mut s = self.lock();
        self.unpack(&mut s, x);
        let mut dx = SVector::<f64, D>::zeros();
        let sc = &mut *s;
        self.sys.residual(t, &sc.q, &sc.v, &sc.a, &mut sc.r);
        sc.r.neg_mut();
        if !self.accelerations(sc) {
            dx.fill(f64::NAN);
            return dx;
        }
        for i in 0..n {
            dx[i] = sc.v[i];
            dx[n + i] = sc.r[i];
        }
        if self.cyclic {
            dx[n] = self.sys.base().torque(t);
        }
        dx[2 * n] = self.sys.work_rate(t, &sc.q, &sc.v);
        dx[2 * n + 1] = 1.0;
        dx
    }

    fn retract(&self, x: &SVector<f64, D>, dx: &SVector<f64, D>) -> SVector<f64, D> {
        x + dx
    }

    /// The projection of a projecting constrained form (`Stabilised`).
    fn normalize(&self, x: &mut SVector<f64, D>) -> bool {
        let Some(st) = self.stab.as_ref().filter(|s| s.project) else {
            return false;
        };
        let n = self.n;
        let mut s = self.lock();
        self.unpack(&mut s, x);
        let Scratch {
            q,
            v,
            m,
            lu,
            aug,
            rhs,
            ..
        } = &mut *s;
        // [M C^T; C 0] [dq; mu] = [0; -C q] gives the M-orthogonal correction dq.
        let k = st.rows.nrows();
        if !self.constant && !self.factor(m, lu, aug) {
            return false;
        }
        for (z, base) in [(&mut *q, 0usize), (&mut *v, n)] {
            rhs.fill(0.0);
            for i in 0..k {
                rhs[n + i] = -(0..n).map(|j| st.rows[(i, j)] * z[j]).sum::<f64>();
            }
            if aug.solve_in_place(rhs).is_err() {
                return false;
            }
            for j in 0..n {
                z[j] += rhs[j];
                // A free hub keeps its momentum (its correction is zero: C has no hub
                // column) in the slot of its rate.
                if !(self.cyclic && base == n && j == 0) {
                    x[base + j] = z[j];
                }
            }
        }
        true
    }

    fn check(&self, t: f64, x: &SVector<f64, D>) -> Result<(), Failure> {
        if !x.iter().all(|c| c.is_finite()) {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t,
                "non-finite beam state",
            ));
        }
        let mut s = self.lock();
        for i in 0..self.n {
            s.q[i] = x[i];
        }
        check_bound(t, self.sys.tip_deflection(&s.q), self.bound)
    }
}

/// An observation with the state it came from (a segmented run continues from it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OdeObs<const D: usize> {
    pub obs: BeamObs,
    pub x: SVector<f64, D>,
}

impl<S: Beamlike, const D: usize> crate::run::Observable for AsOde<S, D> {
    type Obs = OdeObs<D>;
    fn observe(&self, x: &SVector<f64, D>) -> OdeObs<D> {
        OdeObs {
            obs: self.obs(x),
            x: *x,
        }
    }
    fn residual(&self, x: &SVector<f64, D>) -> Option<f64> {
        let st = self.stab.as_ref()?;
        Some(
            (0..st.rows.nrows())
                .map(|i| {
                    (0..self.n)
                        .map(|j| st.rows[(i, j)] * x[j])
                        .sum::<f64>()
                        .abs()
                })
                .fold(0.0, f64::max),
        )
    }
    fn energy(&self, o: &OdeObs<D>) -> f64 {
        o.obs.kinetic + o.obs.strain
    }
}

impl<S: Beamlike + Clone, const D: usize> Clone for AsOde<S, D> {
    fn clone(&self) -> Self {
        AsOde::constrained(self.sys.clone(), self.bound, self.stab.clone())
            .expect("a valid model stays valid")
    }
}

/// Runs method `m` from rest at `t = 0` on the model `build` makes for each segment between
/// breakpoints (`Base::on_segment`): each segment is its own run from the state reached (an
/// adaptive method restarts exactly at the breakpoint, with a fresh initial step), and the
/// outputs are joined (the time and the work integral run on in the state).
#[allow(clippy::too_many_arguments)]
pub fn run_ode<S: Beamlike + Clone, const D: usize, M: OdeMethod>(
    build: &dyn Fn(Base) -> Result<(S, Option<Stabilised>), String>,
    base: Base,
    breakpoints: &[f64],
    m: &M,
    stepping: Stepping,
    grid: &Grid,
    limits: &Limits,
    observe_at: &Observe,
    bound: f64,
) -> Result<RunOutput<BeamObs>, String> {
    if matches!(observe_at, Observe::Steps { .. }) {
        return Err("the beam's runs observe on the grid or at the end".into());
    }
    let segs = super::run::segments(breakpoints, grid.t_end);
    let mut out = RunOutput {
        samples: vec![],
        score_stride: 1,
        failure: None,
        stats: Stats::default(),
        conditioning_min: 1.0,
    };
    let mut x: Option<SVector<f64, D>> = None;
    for &(a, b) in &segs {
        let (model, stab) = build(base.on_segment(a, b))?;
        let sys = AsOde::<S, D>::constrained(model, bound, stab)?;
        let x0 = match x {
            Some(x) => x,
            None => {
                let n = sys.sys.dim();
                sys.state(&DVector::zeros(n), &DVector::zeros(n))
            }
        };
        let g = Grid {
            t_end: b - a,
            ..*grid
        };
        let part = m.run(&sys, x0, stepping, &g, limits, observe_at)?;
        let last = part.samples.last().map(|s| s.obs.x);
        let skip = usize::from(!out.samples.is_empty());
        out.score_stride = part.score_stride;
        out.samples
            .extend(part.samples.iter().skip(skip).map(|s| Sample {
                t: s.t + a,
                obs: s.obs.obs,
                conditioning: s.conditioning,
                residual: s.residual,
            }));
        out.stats += part.stats;
        if part.failure.is_some() {
            out.failure = part.failure.map(|mut f| {
                f.t += a;
                f
            });
            return Ok(out);
        }
        if let Err(f) = limits.check(b, &out.stats) {
            out.failure = Some(f);
            return Ok(out);
        }
        x = last;
    }
    if *observe_at == Observe::Final && out.samples.len() > 2 {
        let last = out.samples.len() - 1;
        out.samples.drain(1..last);
    }
    Ok(out)
}

/// Hairer's componentwise scale: every component is additive.
impl<S: Beamlike, const D: usize> crate::integrate::adaptive_rk::ErrorScale for AsOde<S, D> {
    fn coords(&self, x: &SVector<f64, D>) -> SVector<f64, D> {
        *x
    }
}
