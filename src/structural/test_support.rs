//! Test systems and measurements shared by the structural integrators' tests: linear and
//! nonlinear second-order systems with analytic tangents, an RK4 reference, the step-ladder
//! order measurement, the numerical amplification matrix of a stiff oscillator, the
//! massless-node chain and its reduced system, and the Cartesian pendulum. The shared checks
//! take any unconstrained method, as a `Method<dyn SecondOrder>`.
use nalgebra::{DMatrix, DVector, Matrix4};

use super::method::Method;
use super::newton::NewtonOptions;
use super::state::State;
use super::{Constraints, SecondOrder};
use crate::integrate::{FailureKind, Stats};

/// Newton options well below every discretisation error the tests measure.
pub(crate) fn tight() -> NewtonOptions {
    NewtonOptions {
        tol: 1e-12,
        max_iters: 25,
    }
}

/// One Newton update a step: fails whenever a step needs more.
pub(crate) fn cap_one() -> NewtonOptions {
    NewtonOptions {
        tol: 1e-10,
        max_iters: 1,
    }
}

/// `M a + C v + K q = 0` with constant matrices.
pub(crate) struct Linear {
    m: DMatrix<f64>,
    c: DMatrix<f64>,
    k: DMatrix<f64>,
}

impl Linear {
    /// A 1-DOF oscillator.
    pub fn oscillator(m: f64, c: f64, k: f64) -> Self {
        Linear {
            m: DMatrix::from_element(1, 1, m),
            c: DMatrix::from_element(1, 1, c),
            k: DMatrix::from_element(1, 1, k),
        }
    }

    /// Two coupled masses (frequencies about 1 and 3.2), damping `c` times the identity.
    pub fn two_dof(c: f64) -> Self {
        Linear {
            m: DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 2.0]),
            c: DMatrix::identity(2, 2) * c,
            k: DMatrix::from_row_slice(2, 2, &[11.0, -1.0, -1.0, 2.0]),
        }
    }

    /// `(v^T M v + q^T K q)/2`.
    pub fn energy(&self, st: &State) -> f64 {
        0.5 * (st.v.dot(&(&self.m * &st.v)) + st.q.dot(&(&self.k * &st.q)))
    }

    /// The largest natural frequency.
    pub fn omega_max(&self) -> f64 {
        let minv = self.m.clone().try_inverse().unwrap();
        let eig = (&minv * &self.k).complex_eigenvalues();
        eig.iter().map(|z| z.norm().sqrt()).fold(0.0, f64::max)
    }
}

impl SecondOrder for Linear {
    fn dim(&self) -> usize {
        self.m.nrows()
    }
    fn residual(
        &self,
        _t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        r.gemv(1.0, &self.m, a, 0.0);
        r.gemv(1.0, &self.c, v, 1.0);
        r.gemv(1.0, &self.k, q, 1.0);
    }
    fn tangent(
        &self,
        _t: f64,
        _q: &DVector<f64>,
        _v: &DVector<f64>,
        _a: &DVector<f64>,
        c_m: f64,
        c_c: f64,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s.copy_from(&self.m);
        *s *= c_m;
        *s += &self.c * c_c;
        *s += &self.k * c_k;
    }
}

/// The forced, damped Duffing oscillator
/// `m a + c v + k q + k3 q^3 = F cos(w t)`.
pub(crate) struct Duffing {
    pub m: f64,
    pub c: f64,
    pub k: f64,
    pub k3: f64,
    pub force: f64,
    pub w: f64,
}

impl SecondOrder for Duffing {
    fn dim(&self) -> usize {
        1
    }
    fn residual(
        &self,
        t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        r[0] = self.m * a[0] + self.c * v[0] + self.k * q[0] + self.k3 * q[0].powi(3)
            - self.force * (self.w * t).cos();
    }
    fn tangent(
        &self,
        _t: f64,
        q: &DVector<f64>,
        _v: &DVector<f64>,
        _a: &DVector<f64>,
        c_m: f64,
        c_c: f64,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s[(0, 0)] = c_m * self.m + c_c * self.c + c_k * (self.k + 3.0 * self.k3 * q[0] * q[0]);
    }
}

/// A conservative oscillator with a configuration-dependent mass, from
/// `L = (1 + q^2) v^2 / 2 - q^2/2 - q^4/4`: `(1 + q^2) a + q v^2 + q + q^3 = 0`.
pub(crate) struct VarMass;

impl SecondOrder for VarMass {
    fn dim(&self) -> usize {
        1
    }
    fn residual(
        &self,
        _t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        let (q, v, a) = (q[0], v[0], a[0]);
        r[0] = (1.0 + q * q) * a + q * v * v + q + q * q * q;
    }
    fn tangent(
        &self,
        _t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        c_m: f64,
        c_c: f64,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        let (q, v, a) = (q[0], v[0], a[0]);
        s[(0, 0)] = c_m * (1.0 + q * q)
            + c_c * 2.0 * q * v
            + c_k * (2.0 * q * a + v * v + 1.0 + 3.0 * q * q);
    }
}

/// The pendulum in angle form, `a + (g/L) sin q = 0`.
pub(crate) struct Pendulum {
    pub g_over_l: f64,
}

impl SecondOrder for Pendulum {
    fn dim(&self) -> usize {
        1
    }
    fn residual(
        &self,
        _t: f64,
        q: &DVector<f64>,
        _v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        r[0] = a[0] + self.g_over_l * q[0].sin();
    }
    fn tangent(
        &self,
        _t: f64,
        q: &DVector<f64>,
        _v: &DVector<f64>,
        _a: &DVector<f64>,
        c_m: f64,
        _c_c: f64,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s[(0, 0)] = c_m + c_k * self.g_over_l * q[0].cos();
    }
}

/// `a = -M^{-1} f(t, q, v)` (tests only: allocates).
fn acceleration(sys: &dyn SecondOrder, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> DVector<f64> {
    let n = sys.dim();
    let zero = DVector::zeros(n);
    let mut f = DVector::zeros(n);
    sys.residual(t, q, v, &zero, &mut f);
    let mut m = DMatrix::zeros(n, n);
    sys.tangent(t, q, v, &zero, 1.0, 0.0, 0.0, &mut m);
    -m.lu().solve(&f).expect("regular mass matrix")
}

/// `(q, v)` at `t_end` by classical RK4 with `steps` steps (error about `(t_end/steps)^4`).
pub(crate) fn reference(
    sys: &dyn SecondOrder,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    steps: usize,
) -> (DVector<f64>, DVector<f64>) {
    let (mut q, mut v) = (
        DVector::from_column_slice(q0),
        DVector::from_column_slice(v0),
    );
    let h = t_end / steps as f64;
    for k in 0..steps {
        let t = k as f64 * h;
        let (k1q, k1v) = (v.clone(), acceleration(sys, t, &q, &v));
        let (q2, v2) = (&q + &k1q * (h / 2.0), &v + &k1v * (h / 2.0));
        let (k2q, k2v) = (v2.clone(), acceleration(sys, t + h / 2.0, &q2, &v2));
        let (q3, v3) = (&q + &k2q * (h / 2.0), &v + &k2v * (h / 2.0));
        let (k3q, k3v) = (v3.clone(), acceleration(sys, t + h / 2.0, &q3, &v3));
        let (q4, v4) = (&q + &k3q * h, &v + &k3v * h);
        let (k4q, k4v) = (v4.clone(), acceleration(sys, t + h, &q4, &v4));
        q += (k1q + k2q * 2.0 + k3q * 2.0 + k4q) * (h / 6.0);
        v += (k1v + k2v * 2.0 + k3v * 2.0 + k4v) * (h / 6.0);
    }
    (q, v)
}

/// A nonlinear initial-value problem of the order tests.
pub(crate) struct Case {
    pub name: &'static str,
    pub sys: Box<dyn SecondOrder>,
    pub q0: Vec<f64>,
    pub v0: Vec<f64>,
    pub t_end: f64,
}

/// The forced damped Duffing oscillator, the configuration-dependent mass, and the pendulum
/// at a large amplitude.
pub(crate) fn nonlinear_cases() -> Vec<Case> {
    vec![
        Case {
            name: "duffing",
            sys: Box::new(Duffing {
                m: 1.0,
                c: 0.1,
                k: 1.0,
                k3: 2.0,
                force: 0.5,
                w: 1.3,
            }),
            q0: vec![1.0],
            v0: vec![0.0],
            t_end: 4.0,
        },
        Case {
            name: "var_mass",
            sys: Box::new(VarMass),
            q0: vec![1.0],
            v0: vec![0.5],
            t_end: 4.0,
        },
        Case {
            name: "pendulum",
            sys: Box::new(Pendulum { g_over_l: 1.0 }),
            q0: vec![2.0],
            v0: vec![0.0],
            t_end: 4.0,
        },
    ]
}

/// The step ladder of the order tests (steps over `t_end`).
pub(crate) const LADDER: [usize; 5] = [40, 80, 160, 320, 640];

/// The errors `max(|q - q_ref|, |v - v_ref|)` at `t_end` on the ladder.
pub(crate) fn ladder_errors<M: Method<dyn SecondOrder>>(
    case: &mut Case,
    make: impl Fn() -> M,
) -> Vec<f64> {
    let (qr, vr) = reference(&*case.sys, &case.q0, &case.v0, case.t_end, 40_000);
    LADDER
        .iter()
        .map(|&n| {
            let mut m = make();
            let sys = &mut *case.sys;
            let (mut st, mut stats) = (State::for_system(&*sys), Stats::default());
            st.set(&case.q0, &case.v0);
            m.init(sys, 0.0, &mut st, &mut stats).unwrap();
            let h = case.t_end / n as f64;
            for k in 0..n {
                m.step(sys, k as f64 * h, h, &mut st, &mut stats).unwrap();
            }
            (&st.q - &qr).amax().max((&st.v - &vr).amax())
        })
        .collect()
}

/// Numbers in scientific notation, for the tests' reports.
pub(crate) fn sci(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| format!("{x:.2e}")).collect();
    format!("[{}]", parts.join(", "))
}

/// `log2(e_k / e_{k+1})` of consecutive errors of a halving ladder.
pub(crate) fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// Every observed order of every nonlinear case is within 0.25 of 2.
pub(crate) fn check_order<M: Method<dyn SecondOrder>>(make: impl Fn() -> M, name: &str) {
    for mut case in nonlinear_cases() {
        let errors = ladder_errors(&mut case, &make);
        let p = orders(&errors);
        eprintln!(
            "{name} on {}: errors {}, orders {p:.3?}",
            case.name,
            sci(&errors)
        );
        for o in &p {
            assert!(
                (o - 2.0).abs() <= 0.25,
                "{name} on {}: orders {p:?}",
                case.name
            );
        }
    }
}

/// The spectral radius of one step's amplification matrix on `q'' + q = 0` at `h = 1e4`
/// (`h omega = 1e4`; `spectral_radius_at`), built column by column from steps of the unit states in the scaled
/// variables `(q, h v, h^2 a, h^2 aux)`.
pub(crate) fn spectral_radius<M: Method<dyn SecondOrder>>(m: &mut M) -> f64 {
    spectral_radius_at(m, 1e4)
}

/// The spectral radius of the amplification matrix on `q'' + q = 0` at `h omega = h`.
pub(crate) fn spectral_radius_at<M: Method<dyn SecondOrder>>(m: &mut M, h: f64) -> f64 {
    let mut sys = Linear::oscillator(1.0, 0.0, 1.0);
    let scale = [1.0, h, h * h, h * h];
    let mut amp = Matrix4::zeros();
    for j in 0..4 {
        let mut st = State::for_system(&sys);
        let mut stats = Stats::default();
        let mut unit = [0.0; 4];
        unit[j] = 1.0;
        st.q[0] = unit[0];
        st.v[0] = unit[1] / h;
        st.a[0] = unit[2] / (h * h);
        st.aux[0] = unit[3] / (h * h);
        m.step(&mut sys, 0.0, h, &mut st, &mut stats).unwrap();
        let out = [st.q[0], st.v[0], st.a[0], st.aux[0]];
        for i in 0..4 {
            amp[(i, j)] = out[i] * scale[i];
        }
    }
    amp.complex_eigenvalues()
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max)
}

/// A mass `m` at `x1`, tied to a massless node `x0` by a spring `k2`, the node tied to the
/// ground by `k1`, and a cubic spring `k3 x1^3` from the mass to the ground.
pub(crate) struct MasslessChain {
    pub m: f64,
    pub k1: f64,
    pub k2: f64,
    pub k3: f64,
}

impl MasslessChain {
    /// The node's static share of the mass's displacement, `k2/(k1 + k2)`.
    pub fn share(&self) -> f64 {
        self.k2 / (self.k1 + self.k2)
    }

    /// The reduced system `m a + k_eff x + k3 x^3 = 0`, `k_eff = k1 k2/(k1 + k2)`.
    pub fn reduced(&self) -> Duffing {
        Duffing {
            m: self.m,
            c: 0.0,
            k: self.k1 * self.k2 / (self.k1 + self.k2),
            k3: self.k3,
            force: 0.0,
            w: 0.0,
        }
    }
}

impl SecondOrder for MasslessChain {
    fn dim(&self) -> usize {
        2
    }
    fn residual(
        &self,
        _t: f64,
        q: &DVector<f64>,
        _v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        r[0] = self.k1 * q[0] + self.k2 * (q[0] - q[1]);
        r[1] = self.m * a[1] + self.k2 * (q[1] - q[0]) + self.k3 * q[1].powi(3);
    }
    fn tangent(
        &self,
        _t: f64,
        q: &DVector<f64>,
        _v: &DVector<f64>,
        _a: &DVector<f64>,
        c_m: f64,
        _c_c: f64,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s[(0, 0)] = c_k * (self.k1 + self.k2);
        s[(0, 1)] = -c_k * self.k2;
        s[(1, 0)] = -c_k * self.k2;
        s[(1, 1)] = c_m * self.m + c_k * (self.k2 + 3.0 * self.k3 * q[1] * q[1]);
    }
}

/// Runs the massless chain and its reduced system with fresh methods from `make` for 400
/// steps of 0.05 and returns the largest of: the mass's `q`, `v`, `a` against the reduced
/// system's, and the node's distance from static equilibrium `x0 - share x1`.
pub(crate) fn massless_vs_reduced<M: Method<dyn SecondOrder>>(make: impl Fn() -> M) -> f64 {
    let mut chain = MasslessChain {
        m: 1.0,
        k1: 3.0,
        k2: 1.0,
        k3: 0.5,
    };
    let mut red = chain.reduced();
    let c = chain.share();
    let (mut full, mut small) = (State::for_system(&chain), State::for_system(&red));
    full.set(&[c, 1.0], &[0.2 * c, 0.2]);
    small.set(&[1.0], &[0.2]);
    let (mut mf, mut mr) = (make(), make());
    let mut stats = Stats::default();
    mf.init(&mut chain, 0.0, &mut full, &mut stats).unwrap();
    mr.init(&mut red, 0.0, &mut small, &mut stats).unwrap();
    let h = 0.05;
    let mut worst: f64 = 0.0;
    for k in 0..400 {
        let t = k as f64 * h;
        mf.step(&mut chain, t, h, &mut full, &mut stats).unwrap();
        mr.step(&mut red, t, h, &mut small, &mut stats).unwrap();
        worst = worst
            .max((full.q[1] - small.q[0]).abs())
            .max((full.v[1] - small.v[0]).abs())
            .max((full.a[1] - small.a[0]).abs() / (1.0 + small.a[0].abs()))
            .max((full.q[0] - c * full.q[1]).abs());
    }
    worst
}

/// With a one-update cap, a step of a stiff Duffing oscillator (`h omega = 1`, strong cubic
/// term) is a `newton_failure` at the step's start time, and leaves state and step count
/// alone.
pub(crate) fn newton_cap_check<M: Method<dyn SecondOrder>>(m: &mut M) {
    let mut sys = Duffing {
        m: 1.0,
        c: 0.0,
        k: 1e4,
        k3: 1e6,
        force: 0.0,
        w: 0.0,
    };
    let (mut st, mut stats) = (State::for_system(&sys), Stats::default());
    st.set(&[1.0], &[0.0]);
    m.init(&mut sys, 0.5, &mut st, &mut stats).unwrap();
    let a0 = st.a[0];
    let f = m
        .step(&mut sys, 0.5, 0.01, &mut st, &mut stats)
        .unwrap_err();
    assert_eq!((f.kind, f.t), (FailureKind::NewtonFailure, 0.5), "{f:?}");
    assert!(f.message.contains("max_iters = 1"), "{}", f.message);
    assert_eq!((st.q[0], st.v[0], st.a[0]), (1.0, 0.0, a0));
    assert_eq!((stats.steps, stats.newton_iters), (0, 1));
}

/// A non-finite or non-positive step is a `non_finite` failure that leaves the state alone.
pub(crate) fn bad_step_check<M: Method<dyn SecondOrder>>(m: &mut M) {
    let mut sys = Linear::oscillator(1.0, 0.0, 1.0);
    let (mut st, mut stats) = (State::for_system(&sys), Stats::default());
    st.set(&[1.0], &[0.0]);
    m.init(&mut sys, 0.0, &mut st, &mut stats).unwrap();
    for h in [f64::NAN, f64::INFINITY, 0.0, -1.0] {
        let f = m.step(&mut sys, 0.0, h, &mut st, &mut stats).unwrap_err();
        assert_eq!(f.kind, FailureKind::NonFinite, "{f:?}");
        assert!(f.message.contains("step h"), "{}", f.message);
    }
    assert_eq!((st.q[0], stats.steps), (1.0, 0));
}

/// The planar pendulum in Cartesian coordinates `q = (x, y)`: a mass `m` under gravity
/// `-grav e_y` on a massless rod of length `len` from the origin,
/// `m a + m grav e_y + G^T lambda = 0`, `g = (x^2 + y^2 - len^2)/2`, `G = (x, y)`, so
/// `lambda` is the rod's tension over its length.
pub(crate) struct CartPendulum {
    pub m: f64,
    pub grav: f64,
    pub len: f64,
}

impl CartPendulum {
    /// `(q, v)` of the pendulum at angle `th` from the downward vertical, rate `om`.
    pub fn cartesian(&self, th: f64, om: f64) -> ([f64; 2], [f64; 2]) {
        let l = self.len;
        (
            [l * th.sin(), -l * th.cos()],
            [l * om * th.cos(), l * om * th.sin()],
        )
    }

    /// The multiplier of the exact motion at `(th, om)`: `m (len^2 om^2 + grav len cos th) /
    /// len^2`.
    pub fn lambda(&self, th: f64, om: f64) -> f64 {
        let l = self.len;
        self.m * (l * l * om * om + self.grav * l * th.cos()) / (l * l)
    }
}

impl SecondOrder for CartPendulum {
    fn dim(&self) -> usize {
        2
    }
    fn residual(
        &self,
        _t: f64,
        _q: &DVector<f64>,
        _v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        r[0] = self.m * a[0];
        r[1] = self.m * a[1] + self.m * self.grav;
    }
    fn tangent(
        &self,
        _t: f64,
        _q: &DVector<f64>,
        _v: &DVector<f64>,
        _a: &DVector<f64>,
        c_m: f64,
        _c_c: f64,
        _c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s.fill(0.0);
        s[(0, 0)] = c_m * self.m;
        s[(1, 1)] = c_m * self.m;
    }
}

impl Constraints for CartPendulum {
    fn n_constraints(&self) -> usize {
        1
    }
    fn g(&self, _t: f64, q: &DVector<f64>, out: &mut DVector<f64>) {
        out[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] - self.len * self.len);
    }
    fn jacobian(&self, _t: f64, q: &DVector<f64>, out: &mut DMatrix<f64>) {
        out[(0, 0)] = q[0];
        out[(0, 1)] = q[1];
    }
    fn add_lambda_tangent(
        &self,
        _t: f64,
        _q: &DVector<f64>,
        lambda: &DVector<f64>,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s[(0, 0)] += c_k * lambda[0];
        s[(1, 1)] += c_k * lambda[0];
    }
}
