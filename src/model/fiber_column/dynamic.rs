//! The column under ground acceleration (the `rc_pulse` scene): a lumped top mass `m` in
//! both translations (rotations massless), mass-proportional damping `C = a0 M`, the static
//! load `f_static` (the axial load) and the ground-motion load `F_g(t) = -M 1 a_g(t)` along
//! global x, integrated in time by one of four one-step implicit schemes on the relative
//! displacement `u`, each step solved by the column's Newton iteration (`column.rs`).
//!
//! **Generalized-alpha family** (Chung & Hulbert 1993, "A time integration algorithm for
//! structural dynamics with improved numerical dissipation: the generalized-alpha method",
//! J. Appl. Mech. 60, 371-375): Newmark's kinematics
//! `u_{n+1} = u_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1})`,
//! `v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1})`, and the balance
//!
//! ```text
//! M ((1-am) a_{n+1} + am a_n) + C ((1-af) v_{n+1} + af v_n)
//!     + (1-af) f(u_{n+1}) + af f_n = (1-af) F_{n+1} + af F_n
//! ```
//!
//! with `gamma = 1/2 - am + af`, `beta = (1 - am + af)^2 / 4` (second order, unconditionally
//! stable for linear problems) and, from the spectral radius at infinite frequency,
//! `am = (2 rho - 1)/(rho + 1)`, `af = rho/(rho + 1)`. `Newmark` is `am = af = 0` (average
//! acceleration, beta 1/4, gamma 1/2); `Hht { alpha }` (Hilber, Hughes & Taylor 1977,
//! "Improved numerical dissipation for time integration algorithms in structural dynamics",
//! EESD 5, 283-292; `alpha` in [-1/3, 0]) is `am = 0`, `af = -alpha`; `GenAlpha { rho_inf }`
//! uses the pair above. (The formulas are stated here in full; the papers' equation numbers
//! were not checked.)
//!
//! *The internal force at the intermediate point.* The linear theory weights `K d`; for this
//! path-dependent structure the weighted forces `(1-af) f(u_{n+1}) + af f_n` are used, with
//! `f_n` the committed internal force of the last converged state stored by the driver. The
//! material state determination is then always carried out at the end-of-step configuration
//! `u_{n+1}` and the committed history is that of the end-points: the alternative, one state
//! determination at `u_{n+1-af} = (1-af) u_{n+1} + af u_n`, would commit fibre states at a
//! configuration the structure never occupies at a step end, and the hysteretic work booked
//! by the fibres would belong to that other path. The weighted-force form is the one whose
//! accuracy and dissipation Erlicher, Bonaventura & Bursi (2002, Comput. Mech. 28, 83-104)
//! analyse for nonlinear problems; it keeps second order for smooth responses.
//!
//! **Midpoint** (energy-consistent): `(u_{n+1} - u_n)/h = (v_n + v_{n+1})/2 =: v_bar` and
//! `M (v_{n+1} - v_n)/h + C v_bar + f_bar = (F_n + F_{n+1})/2` with
//! `f_bar = (f_n + f(u_{n+1}))/2 + e M du / (du . M du)`, `du = u_{n+1} - u_n`,
//! `e = dW - du . (f_n + f_{n+1})/2` and `dW` the elements' own (fibre-trapezoid) work over
//! the step. Dotting the balance with `du = h v_bar` gives, exactly (to the Newton tolerance),
//!
//! ```text
//! (1/2 v^T M v)_{n+1} - (1/2 v^T M v)_n + h v_bar^T C v_bar + dW = du . (F_n + F_{n+1})/2,
//! ```
//!
//! the energy balance below with every term as booked (the correction is skipped where `e`
//! is below the round-off of the work sums, 64 ulps, so the closure is to that resolution). Without the correction `e` (which is
//! `O(h^3)` per step: the fibre and structural trapezoids differ only through the change of
//! the corotational transformation over the step) the scheme is algebraically Newmark's
//! average-acceleration rule, because that rule's equilibrium at `t_n` and `t_{n+1}`, averaged,
//! is this balance: so `Midpoint` and `Newmark` differ by `O(h^2)` only through `e`.
//!
//! **Energies** (all counted from the state handed to [`Dynamic::new`], so all are 0 there;
//! one quadrature for every non-conservative force: the trapezoid of the force along the
//! discrete displacement path, `sum du . (g_n + g_{n+1})/2`): `kinetic = 1/2 v^T M v`;
//! `strain` and `hysteretic` the change of the elements' recoverable energy and of their
//! dissipated energy (work - recoverable, the work by the fibres' trapezoid,
//! [`Column::energies`]); `damping = sum du . C (v_n + v_{n+1})/2`;
//! `input = sum du . (F_n + F_{n+1})/2` with `F = f_static + F_g` (the axial load's work through
//! the axial shortening is input work). `balance = kinetic + strain + hysteretic + damping -
//! input`. By the identity above it vanishes for `Midpoint` to the Newton tolerance; for
//! `Newmark` it is the accumulated `-e`, `O(h^2)`; for HHT and generalized-alpha it also holds
//! their algorithmic dissipation (and `du != h (v_n + v_{n+1})/2` at `O(h^3)` per step).
//!
//! Invariants: between steps the column is committed and `u, v, a` are the scheme's state at
//! `t = n h`; a failed step leaves everything unchanged. The start is at rest in static
//! equilibrium (`a_0 = -a_g(0)` along x). No allocation per step. Where it fails: a step whose
//! Newton iteration fails returns the typed `NewtonFailure`; the schemes' stability is proven
//! for linear problems only.
use nalgebra::{DMatrix, DVector, Vector3};

use crate::rotation::RotationChart;
use crate::structural::gen_alpha::Coefficients;
use super::column::{Algorithm, Column, Inertia, NewtonFailure, StepCount};

/// The time-integration scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scheme {
    /// Average acceleration (beta 1/4, gamma 1/2).
    Newmark,
    /// Hilber-Hughes-Taylor, `alpha` in [-1/3, 0].
    Hht { alpha: f64 },
    /// Chung-Hulbert generalized-alpha with spectral radius `rho_inf` in [0, 1].
    GenAlpha { rho_inf: f64 },
    /// The energy-consistent midpoint rule (trapezoidal internal force with the element-work
    /// correction).
    Midpoint,
}

/// The energies since the start of the run (J).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energies {
    pub kinetic: f64,
    /// Change of the elements' recoverable energy.
    pub strain: f64,
    /// Change of the energy dissipated in the elements (work - recoverable).
    pub hysteretic: f64,
    pub damping: f64,
    /// Work of the ground-motion load and of the static load.
    pub input: f64,
}

impl Energies {
    /// `kinetic + strain + hysteretic + damping - input` (0 for an exact balance).
    pub fn balance(&self) -> f64 {
        self.kinetic + self.strain + self.hysteretic + self.damping - self.input
    }
}

/// The dynamic driver: the column, the scheme's state and the energy books.
pub struct Dynamic<C: RotationChart> {
    column: Column<C>,
    /// The support's reaction after the last step.
    base: Vector3<f64>,
    scheme: Scheme,
    /// `(am, af, beta, gamma)`.
    params: (f64, f64, f64, f64),
    h: f64,
    n: u64,
    m: f64,
    a0: f64,
    /// The massive unknowns (top x, top z); the ground acts on the first.
    dofs: [usize; 2],
    mass: DVector<f64>,
    f_static: DVector<f64>,
    f_ext: DVector<f64>,
    f_old: DVector<f64>,
    u: DVector<f64>,
    v: DVector<f64>,
    a: DVector<f64>,
    u_pred: DVector<f64>,
    v_pred: DVector<f64>,
    u_eff: DVector<f64>,
    v_eff: DVector<f64>,
    top: Vector3<f64>,
    work0: (f64, f64),
    kinetic: f64,
    damping: f64,
    input: f64,
    /// Newton iterations since construction.
    pub iterations: usize,
}

impl<C: RotationChart> Dynamic<C> {
    /// `column` after the axial prelude, `f_static` its static load (the axial load, on the
    /// top's translations only), top lumped mass in both translations, `a0` of `C = a0 M`,
    /// the scheme and the step `h`.
    ///
    /// # Example
    ///
    /// An elastic cantilever released from rest under a short ground pulse: the energy
    /// balance of the midpoint rule closes to round-off.
    ///
    /// ```
    /// use mbdbench::model::fiber_column::basic::{Basic, ForceBased};
    /// use mbdbench::rotation::So3;
    /// use mbdbench::model::fiber_column::column::{Algorithm, Column};
    /// use mbdbench::model::fiber_column::dynamic::{Dynamic, Scheme};
    /// use mbdbench::model::fiber_column::section::{ElasticSection, Section};
    /// use nalgebra::DVector;
    ///
    /// let s = Section::Elastic(ElasticSection::new(1e9, 1e7, 1e7).unwrap());
    /// let e = Basic::Force(Box::new(ForceBased::new(3.0, 1e7, &s, 3, 1e-14, 20).unwrap()));
    /// let col: Column<So3> = Column::new(3.0, vec![e]).unwrap();
    /// let f = DVector::zeros(col.dim());
    /// let mut d = Dynamic::new(col, f, 1e4, 0.1, Scheme::Midpoint, 1e-3).unwrap();
    /// let ground = |t: f64| if t < 0.05 { 2.0 } else { 0.0 };
    /// for _ in 0..200 {
    ///     d.step(&ground, 1e-16, 20, Algorithm::Newton).unwrap();
    /// }
    /// let e = d.energies();
    /// assert!(e.kinetic + e.strain > 0.0);
    /// assert!(e.balance().abs() < 1e-9 * e.input.abs().max(e.kinetic));
    /// ```
    pub fn new(
        mut column: Column<C>,
        f_static: DVector<f64>,
        top_mass: f64,
        a0: f64,
        scheme: Scheme,
        h: f64,
    ) -> Result<Self, String> {
        let dim = column.dim();
        if f_static.len() != dim {
            return Err(format!(
                "f_static has {} entries, not {dim}",
                f_static.len()
            ));
        }
        let top = column.top_dof(0);
        if (0..dim).any(|i| f_static[i] != 0.0 && !(top..top + 3).contains(&i)) {
            return Err("f_static may load the top's translations only".into());
        }
        if !top_mass.is_finite() || top_mass <= 0.0 {
            return Err(format!("top mass {top_mass} is not positive"));
        }
        if !a0.is_finite() || a0 < 0.0 {
            return Err(format!("damping coefficient {a0} is negative"));
        }
        if !h.is_finite() || h <= 0.0 {
            return Err(format!("step {h} is not positive"));
        }
        let params = match scheme {
            Scheme::Newmark => (0.0, 0.0, 0.25, 0.5),
            // The one derivation of the family's coefficients (`structural::gen_alpha`).
            Scheme::Hht { alpha } => {
                let c = Coefficients::hht(alpha, "hht")?;
                (c.alpha_m, c.alpha_f, c.beta, c.gamma)
            }
            Scheme::GenAlpha { rho_inf } => {
                let c = Coefficients::new(rho_inf, "gen_alpha")?;
                (c.alpha_m, c.alpha_f, c.beta, c.gamma)
            }
            Scheme::Midpoint => (0.5, 0.5, 0.25, 0.5),
        };
        let dofs = [column.top_dof(0), column.top_dof(2)];
        let mut mass = DVector::zeros(dim);
        let mut u = DVector::zeros(dim);
        let d = column.top_displacement();
        for (i, x) in [(dofs[0], d.x), (dofs[1], d.z)] {
            mass[i] = top_mass;
            u[i] = x;
        }
        // The internal force of the committed state (assembled if it is not current).
        column.tangent().map_err(|e| e.to_string())?;
        let f_old = column.internal_force().clone();
        let work0 = column.energies();
        Ok(Self {
            column,
            base: Vector3::zeros(),
            scheme,
            params,
            h,
            n: 0,
            m: top_mass,
            a0,
            dofs,
            mass,
            f_ext: f_static.clone(),
            f_static,
            f_old,
            v: DVector::zeros(dim),
            a: DVector::zeros(dim),
            u_pred: DVector::zeros(dim),
            v_pred: DVector::zeros(dim),
            u_eff: DVector::zeros(dim),
            v_eff: DVector::zeros(dim),
            u,
            top: d,
            work0,
            kinetic: 0.0,
            damping: 0.0,
            input: 0.0,
            iterations: 0,
        })
    }

    /// One step `t -> t + h` under the ground acceleration `ground(t)` (m/s^2, along global
    /// x), Newton tolerance (EnergyIncr, J) and iteration limit; commits on success, leaves
    /// the state unchanged on failure.
    pub fn step(
        &mut self,
        ground: &dyn Fn(f64) -> f64,
        tol: f64,
        max_iter: usize,
        algorithm: Algorithm,
    ) -> Result<StepCount, NewtonFailure> {
        let (am, af, beta, gamma) = self.params;
        let h = self.h;
        let t0 = self.n as f64 * h;
        let t1 = (self.n + 1) as f64 * h;
        let (g0, g1) = (ground(t0), ground(t1));
        let [ix, _] = self.dofs;
        if self.n == 0 && g0 != 0.0 {
            // At rest in static equilibrium: M a_0 = F_g(0).
            self.a[ix] = -g0;
        }
        let midpoint = self.scheme == Scheme::Midpoint;
        for i in self.dofs {
            self.u_pred[i] = self.u[i] + self.v[i] * h + self.a[i] * (h * h * (0.5 - beta));
            self.v_pred[i] = self.v[i] + self.a[i] * (h * (1.0 - gamma));
        }
        self.f_ext.copy_from(&self.f_static);
        let (fg0, fg1) = (-self.m * g0, -self.m * g1);
        let (c_a, c_v, w_int);
        if midpoint {
            // a_eff = (v_{n+1} - v_n)/h = (2/h^2)(u - u_n - h v_n), v_eff = (u - u_n)/h.
            for i in self.dofs {
                self.u_eff[i] = self.u[i] + h * self.v[i];
                self.v_eff[i] = self.v[i];
            }
            (c_a, c_v, w_int) = (2.0 / (h * h), 0.5 * h, 0.5);
            self.f_ext[ix] += 0.5 * (fg0 + fg1);
        } else if am == 0.0 && af == 0.0 {
            self.u_eff.copy_from(&self.u_pred);
            self.v_eff.copy_from(&self.v_pred);
            (c_a, c_v, w_int) = (1.0 / (beta * h * h), gamma * h, 1.0);
            self.f_ext[ix] += fg1;
        } else {
            // a_eff = (1-am) a_{n+1} + am a_n, v_eff = (1-af) v_{n+1} + af v_n, both affine
            // in u through Newmark's a_{n+1} = (u - u_pred)/(beta h^2).
            c_a = (1.0 - am) / (beta * h * h);
            c_v = (1.0 - af) * gamma * h / (1.0 - am);
            w_int = 1.0 - af;
            for i in self.dofs {
                self.u_eff[i] = self.u_pred[i] - am * self.a[i] / c_a;
                self.v_eff[i] = (1.0 - af) * self.v_pred[i] + af * self.v[i] - c_v * am * self.a[i];
            }
            self.f_ext[ix] += (1.0 - af) * fg1 + af * fg0;
        }
        let work_consistent = midpoint.then(|| self.column.energies().0);
        let inertia = Inertia {
            mass: &self.mass,
            a0: self.a0,
            c_a,
            c_v,
            u_pred: &self.u_eff,
            v_pred: &self.v_eff,
            w_int,
            f_old: (w_int != 1.0).then_some(&self.f_old),
            work_consistent,
        };
        let (count, base) =
            self.column
                .step_dynamic(&self.f_ext, None, Some(inertia), tol, max_iter, algorithm)?;
        self.base = base;
        self.iterations += count.iterations;
        // The scheme's new state and the energy books.
        let d = self.column.top_displacement();
        let du_top = d - self.top;
        let mut kinetic = 0.0;
        for (i, x) in [(self.dofs[0], d.x), (self.dofs[1], d.z)] {
            let v_old = self.v[i];
            if midpoint {
                let v_new = 2.0 * (x - self.u[i]) / h - v_old;
                self.a[i] = (v_new - v_old) / h;
                self.v[i] = v_new;
            } else {
                self.a[i] = (x - self.u_pred[i]) / (beta * h * h);
                self.v[i] = self.v_pred[i] + gamma * h * self.a[i];
            }
            let du = x - self.u[i];
            self.damping += self.a0 * self.m * du * 0.5 * (v_old + self.v[i]);
            kinetic += 0.5 * self.m * self.v[i] * self.v[i];
            self.u[i] = x;
        }
        let top = self.column.top_dof(0);
        for c in 0..3 {
            self.input += du_top[c] * self.f_static[top + c];
        }
        self.input += du_top.x * 0.5 * (fg0 + fg1);
        self.kinetic = kinetic;
        self.top = d;
        self.f_old.copy_from(self.column.internal_force());
        self.n += 1;
        Ok(count)
    }

    /// The support's reaction on the column at the end of the last step (N): the base shear
    /// is `-x`, the axial force `-z` (zero before the first step).
    pub fn base_reaction(&self) -> Vector3<f64> {
        self.base
    }

    /// The time reached (`n h`).
    pub fn t(&self) -> f64 {
        self.n as f64 * self.h
    }

    /// The step.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// The column.
    pub fn column(&self) -> &Column<C> {
        &self.column
    }

    /// The top node's velocity relative to the ground (its y component is 0: no mass).
    pub fn velocity_top(&self) -> Vector3<f64> {
        Vector3::new(self.v[self.dofs[0]], 0.0, self.v[self.dofs[1]])
    }

    /// The energies since the start.
    pub fn energies(&self) -> Energies {
        let (w, r) = self.column.energies();
        let (w0, r0) = self.work0;
        Energies {
            kinetic: self.kinetic,
            strain: r - r0,
            hysteretic: (w - r) - (w0 - r0),
            damping: self.damping,
            input: self.input,
        }
    }
}

/// `omega_1` by static condensation of the column's current tangent onto the top node's two
/// translations x, z (the rotation and other unknowns condensed out): the smallest
/// `sqrt(eig(K_c / m))`.
///
/// # Example
///
/// An elastic cantilever: `K_c,xx = 3 EI / L^3` and the axial `EA / L`, so
/// `omega_1 = sqrt(3 EI / (m L^3))` when that is the smaller.
///
/// ```
/// use mbdbench::model::fiber_column::basic::{Basic, ForceBased};
/// use mbdbench::rotation::So3;
/// use mbdbench::model::fiber_column::column::Column;
/// use mbdbench::model::fiber_column::dynamic::omega1;
/// use mbdbench::model::fiber_column::section::{ElasticSection, Section};
///
/// let s = Section::Elastic(ElasticSection::new(1e9, 1e7, 1e7).unwrap());
/// let e = Basic::Force(Box::new(ForceBased::new(3.0, 1e7, &s, 3, 1e-14, 20).unwrap()));
/// let mut col: Column<So3> = Column::new(3.0, vec![e]).unwrap();
/// let w = omega1(&mut col, 1e4).unwrap();
/// let exact = (3.0 * 1e7 / (1e4 * 27.0f64)).sqrt();
/// assert!((w - exact).abs() < 1e-9 * exact);
/// ```
pub fn omega1<C: RotationChart>(column: &mut Column<C>, top_mass: f64) -> Result<f64, String> {
    let t = [column.top_dof(0), column.top_dof(2)];
    let k = column.tangent().map_err(|e| e.to_string())?;
    let n = k.nrows();
    let o: Vec<usize> = (0..n).filter(|i| !t.contains(i)).collect();
    let koo = DMatrix::from_fn(o.len(), o.len(), |i, j| k[(o[i], o[j])]);
    let kot = DMatrix::from_fn(o.len(), 2, |i, j| k[(o[i], t[j])]);
    let kto = DMatrix::from_fn(2, o.len(), |i, j| k[(t[i], o[j])]);
    let x = koo
        .lu()
        .solve(&kot)
        .ok_or("the condensed-out block of the tangent is singular")?;
    let kc = DMatrix::from_fn(2, 2, |i, j| k[(t[i], t[j])]) - kto * x;
    let (tr, det) = (kc[(0, 0)] + kc[(1, 1)], kc.determinant());
    let disc = 0.25 * tr * tr - det;
    if disc < 0.0 {
        return Err(format!(
            "complex eigenvalues of the condensed tangent ({disc:e})"
        ));
    }
    // The smaller root without cancellation: det / (the larger).
    let lam = det / (0.5 * tr + disc.sqrt());
    if lam.is_nan() || lam <= 0.0 {
        return Err(format!("the condensed tangent is not positive ({lam:e})"));
    }
    Ok((lam / top_mass).sqrt())
}
