//! The column under ground acceleration (the `rc_pulse` scene) as a system of the structural
//! time integrators: [`ground_motion`] makes the column, after its axial prelude, a
//! [`Path`] with a lumped top mass `m` in both translations (rotations massless),
//! mass-proportional damping `C = a0 M`, the static load `f_static` (the axial load) and the
//! ground-motion load `F_g(t) = -M 1 a_g(t)` along global x, so that `newmark`, `hht`,
//! `gen_alpha` (the structural module's, as on the flexible beam) and the energy-consistent
//! `midpoint` step it on the relative displacement `u`, each step solved by the column's
//! Newton iteration (`structural::equilibrium`). The schemes' equations, the weighted
//! internal force of the generalized-alpha family on a path-dependent structure and the
//! midpoint rule's energy-consistent correction are in `structural/path_step.rs`.
//!
//! **Energies** (all counted from the state after the prelude, so all are 0 there; one
//! quadrature for every non-conservative force: the trapezoid of the force along the
//! discrete displacement path): `kinetic = 1/2 v^T M v`, `damping` and `input` (the
//! ground motion's load and the axial load, whose work through the axial shortening is input
//! work) as the path books them; `strain` and `hysteretic` the change of the elements'
//! recoverable energy and of their dissipated energy (work - recoverable, the work by the
//! fibres' trapezoid, [`Column::energies`]). `balance = kinetic + strain + hysteretic +
//! damping - input` vanishes for the midpoint rule to the Newton tolerance; for Newmark it is
//! the accumulated `O(h^2)` difference of the fibre and structural trapezoids; for HHT and
//! generalized-alpha it also holds their algorithmic dissipation.
//!
//! Invariants: the start is at rest in static equilibrium (`a_0 = -a_g(0)` along x). Where
//! it fails: the inputs [`ground_motion`] checks; the steps' failures are the integrators'.
use nalgebra::{DMatrix, DVector};

use super::case::Loading;
use super::column::Column;
use crate::rotation::RotationChart;
use crate::structural::equilibrium::Equilibrium;
use crate::structural::path_step::{Path, Series};

/// The ground acceleration of a scene's loading (m/s^2, along global x; 0 for a loading
/// without one).
#[derive(Debug, Clone)]
pub struct Ground(pub Loading);

impl Series for Ground {
    fn at(&self, t: f64) -> f64 {
        self.0.ground(t)
    }
}

/// The column under a ground motion, for the structural methods (module docs).
pub type Shaken<C, E, G> = Path<Column<C>, E, G>;

/// `column` after the axial prelude with `f_static` its static load (the axial load, on
/// the top's translations only), top lumped mass `top_mass` in both translations, `a0` of
/// `C = a0 M`, the solver of its steps and the ground acceleration `ground`; an error names
/// a bad input.
///
/// # Example
///
/// An elastic cantilever released from rest under a short ground pulse, stepped by the
/// midpoint rule: its energy balance closes to round-off.
///
/// ```
/// use mbdbench::integrate::Stats;
/// use mbdbench::model::fiber_column::basic::{Basic, ForceBased};
/// use mbdbench::model::fiber_column::column::Column;
/// use mbdbench::model::fiber_column::dynamic::{energies, ground_motion};
/// use mbdbench::model::fiber_column::section::{ElasticSection, Section};
/// use mbdbench::rotation::So3;
/// use mbdbench::structural::equilibrium::Newton;
/// use mbdbench::structural::method::Method;
/// use mbdbench::structural::midpoint::Midpoint;
/// use nalgebra::DVector;
///
/// let s = Section::Elastic(ElasticSection::new(1e9, 1e7, 1e7).unwrap());
/// let e = Basic::Force(Box::new(ForceBased::new(3.0, 1e7, &s, 3, 1e-14, 20).unwrap()));
/// let col: Column<So3> = Column::new(3.0, vec![e]).unwrap();
/// let work0 = col.energies();
/// let f = DVector::zeros(col.dim());
/// let ground = |t: f64| if t < 0.05 { 2.0 } else { 0.0 };
/// let newton = Newton::new(1e-16, 20).unwrap();
/// let mut p = ground_motion(col, f, 1e4, 0.1, newton, ground).unwrap();
/// let (mut m, mut stats) = (Midpoint, Stats::default());
/// let mut st = Method::new_state(&m, &p);
/// m.init(&mut p, 0.0, &mut st, &mut stats).unwrap();
/// for k in 0..200 {
///     m.step(&mut p, k as f64 * 1e-3, 1e-3, &mut st, &mut stats).unwrap();
/// }
/// let e = energies(&p, work0);
/// assert!(e.kinetic + e.strain > 0.0);
/// assert!(e.balance().abs() < 1e-9 * e.input.abs().max(e.kinetic));
/// ```
pub fn ground_motion<C: RotationChart, E: Equilibrium<Column<C>>, G: Series>(
    column: Column<C>,
    f_static: DVector<f64>,
    top_mass: f64,
    a0: f64,
    solver: E,
    ground: G,
) -> Result<Shaken<C, E, G>, String> {
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
    let (ix, iz) = (column.top_dof(0), column.top_dof(2));
    let mut mass = DVector::zeros(dim);
    mass[ix] = top_mass;
    mass[iz] = top_mass;
    let mut pattern = DVector::zeros(dim);
    pattern[ix] = -top_mass;
    Path::new(column, solver, mass, a0, f_static, pattern, ground)
}

/// The energies since the start (J).
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

/// The energies of the shaken column since the state whose elements' work and recoverable
/// energy were `work0` ([`Column::energies`] after the prelude).
pub fn energies<C: RotationChart, E: Equilibrium<Column<C>>, G: Series>(
    p: &Shaken<C, E, G>,
    work0: (f64, f64),
) -> Energies {
    let (w, r) = p.system.energies();
    let (w0, r0) = work0;
    Energies {
        kinetic: p.kinetic(),
        strain: r - r0,
        hysteretic: (w - r) - (w0 - r0),
        damping: p.damping(),
        input: p.input(),
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
