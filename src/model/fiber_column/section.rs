//! Beam cross-sections: the fiber section (uniaxial fibers at points `(y, z)` of the section)
//! and the linear elastic section, with the section deformations `e = [eps0, kappa_z,
//! kappa_y]` (axial strain at the reference axis, curvatures about local z and y) and the
//! section forces `s = [N, Mz, My]`.
//!
//! A fiber at `(y, z)` strains by `eps = eps0 - y kappa_z + z kappa_y` (plane sections;
//! Spacone, Filippou & Taucer 1996, eq. 10), so `s = sum_f A_f sigma_f [1, -y_f, z_f]` and
//! the section tangent is `k_s = sum_f A_f E_f [1, -y, z]^T [1, -y, z]`, consistent with `s`
//! when the fibers' tangents are. Torsion is not a fiber quantity: the elements carry it
//! elastically (`GJ`). Trial states start from the last committed state (the materials'),
//! so setting the same `e` twice gives the same `s`.
//!
//! Cost: the fiber loop is the column's hot spot (60 % of a cyclic run). The fibers are held
//! by material model, each model's states in one array, so the loop dispatches statically
//! over compact states (the enum `Material` pads every fiber to its largest model); this
//! halved the cost of `rc_cyclic_c01` (0.40 s to 0.22 s, pinned, one core), bit for bit the
//! same results: within a model the fibers keep their given order, and the models are summed
//! in a fixed order (elastic, Concrete01, Concrete02, Steel01, Steel02), which is the given
//! order whenever, as in the catalogue's sections, the concrete fibers come before the bars.
//!
//! Where it fails: a section whose fibers all lie on one line through the centroid has a
//! singular `k_s` (no stiffness about that line); `FiberSection::new` refuses a section with
//! no fiber or a non-positive area, and the case loader checks the fibers lie in the section.
use nalgebra::{Matrix3, Vector3};

use super::material::{
    Concrete01, Concrete02, Elastic, Material, Steel01, Steel02, Uniaxial,
};

/// One fiber: position in the section (local y, z), area, material with its state.
#[derive(Debug, Clone)]
pub struct Fiber {
    pub y: f64,
    pub z: f64,
    pub area: f64,
    pub material: Material,
}

/// Where a fiber acts: `a = [1, -y, z]` scaled by nothing (the strain is `a . e`) and its
/// area.
#[derive(Debug, Clone, Copy)]
struct Place {
    ny: f64,
    z: f64,
    area: f64,
}

/// The fibers of one material model, in the order they were given: static dispatch and
/// compact state in the hot loop (each model's state is stored without the enum's padding
/// to the largest model).
#[derive(Debug, Clone)]
struct Group<M> {
    at: Vec<Place>,
    m: Vec<M>,
}

impl<M> Default for Group<M> {
    fn default() -> Self {
        Self {
            at: vec![],
            m: vec![],
        }
    }
}

/// The section sums of a trial state: forces and the six distinct tangent entries.
#[derive(Default)]
struct Sums {
    n: f64,
    mz: f64,
    my: f64,
    k: [f64; 6],
}

impl<M: Uniaxial> Group<M> {
    #[inline]
    fn set_trial(&mut self, e: &Vector3<f64>, sums: &mut Sums) {
        for (p, m) in self.at.iter().zip(&mut self.m) {
            let (sigma, et) = m.set_trial_strain(e.x + p.ny * e.y + p.z * e.z);
            let (fa, ka) = (sigma * p.area, et * p.area);
            sums.n += fa;
            sums.mz += p.ny * fa;
            sums.my += p.z * fa;
            sums.k[0] += ka;
            sums.k[1] += p.ny * ka;
            sums.k[2] += p.z * ka;
            sums.k[3] += p.ny * p.ny * ka;
            sums.k[4] += p.ny * p.z * ka;
            sums.k[5] += p.z * p.z * ka;
        }
    }

    fn initial_tangent(&self, k: &mut Matrix3<f64>) {
        for (p, m) in self.at.iter().zip(&self.m) {
            let a = Vector3::new(1.0, p.ny, p.z);
            *k += a * a.transpose() * (m.initial_tangent() * p.area);
        }
    }

    fn commit(&mut self) {
        self.m.iter_mut().for_each(|m| m.commit());
    }

    fn revert(&mut self) {
        self.m.iter_mut().for_each(|m| m.revert_to_last_commit());
    }

    /// Adds `A_f g(material_f)` of each fiber to `total`, one after the other.
    fn add_to(&self, total: &mut f64, g: impl Fn(&M) -> f64) {
        for (p, m) in self.at.iter().zip(&self.m) {
            *total += p.area * g(m);
        }
    }
}

/// A section of uniaxial fibers, held by material model (`Group`): the state determination
/// sums the fibers of each model in their given order, the models in a fixed order.
#[derive(Debug, Clone)]
pub struct FiberSection {
    /// The fibers as given, with their virgin materials (the layout; not the state).
    fibers: Vec<Fiber>,
    elastic: Group<Elastic>,
    concrete01: Group<Concrete01>,
    concrete02: Group<Concrete02>,
    steel01: Group<Steel01>,
    steel02: Group<Steel02>,
}

/// Applies `$body` to each of the section's material groups in turn.
macro_rules! each_group {
    ($s:expr, $g:ident => $body:expr) => {{
        {
            let $g = &$s.elastic;
            $body
        }
        {
            let $g = &$s.concrete01;
            $body
        }
        {
            let $g = &$s.concrete02;
            $body
        }
        {
            let $g = &$s.steel01;
            $body
        }
        {
            let $g = &$s.steel02;
            $body
        }
    }};
    (mut $s:expr, $g:ident => $body:expr) => {{
        {
            let $g = &mut $s.elastic;
            $body
        }
        {
            let $g = &mut $s.concrete01;
            $body
        }
        {
            let $g = &mut $s.concrete02;
            $body
        }
        {
            let $g = &mut $s.steel01;
            $body
        }
        {
            let $g = &mut $s.steel02;
            $body
        }
    }};
}

impl FiberSection {
    /// A section from its fibers. Errors for no fiber or a fiber area that is not positive.
    pub fn new(fibers: Vec<Fiber>) -> Result<Self, String> {
        if fibers.is_empty() {
            return Err("a fiber section needs at least one fiber".into());
        }
        for (i, f) in fibers.iter().enumerate() {
            if !(f.area > 0.0 && f.area.is_finite() && f.y.is_finite() && f.z.is_finite()) {
                return Err(format!(
                    "fiber {i} at ({}, {}) has area {} (must be positive and finite)",
                    f.y, f.z, f.area
                ));
            }
        }
        let mut s = Self {
            fibers: vec![],
            elastic: Group::default(),
            concrete01: Group::default(),
            concrete02: Group::default(),
            steel01: Group::default(),
            steel02: Group::default(),
        };
        for f in &fibers {
            let at = Place {
                ny: -f.y,
                z: f.z,
                area: f.area,
            };
            fn push<M>(g: &mut Group<M>, at: Place, m: M) {
                g.at.push(at);
                g.m.push(m);
            }
            match f.material {
                Material::Elastic(m) => push(&mut s.elastic, at, m),
                Material::Concrete01(m) => push(&mut s.concrete01, at, m),
                Material::Concrete02(m) => push(&mut s.concrete02, at, m),
                Material::Steel01(m) => push(&mut s.steel01, at, m),
                Material::Steel02(m) => push(&mut s.steel02, at, m),
            }
        }
        s.fibers = fibers;
        Ok(s)
    }

    /// The fibers as given (positions, areas and their materials' virgin states).
    pub fn fibers(&self) -> &[Fiber] {
        &self.fibers
    }

    /// The bytes a section holds per fiber: the fiber as given, its place and its material's
    /// state in its group (at most the largest model's).
    pub fn bytes_per_fiber() -> usize {
        std::mem::size_of::<Fiber>() + std::mem::size_of::<Place>() + std::mem::size_of::<Material>()
    }

    #[inline]
    fn set_trial(&mut self, e: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
        let mut sums = Sums::default();
        each_group!(mut self, g => g.set_trial(e, &mut sums));
        let [k00, k01, k02, k11, k12, k22] = sums.k;
        let k = Matrix3::new(k00, k01, k02, k01, k11, k12, k02, k12, k22);
        (Vector3::new(sums.n, sums.mz, sums.my), k)
    }

    fn initial_tangent(&self) -> Matrix3<f64> {
        let mut k = Matrix3::zeros();
        each_group!(self, g => g.initial_tangent(&mut k));
        k
    }

    /// `sum_f A_f w_f`, the fibers' work densities (J/m).
    fn work(&self) -> f64 {
        let mut total = 0.0;
        each_group!(self, g => g.add_to(&mut total, |m| m.work()));
        total
    }

    /// `sum_f A_f u_f`, the fibers' recoverable energy densities (J/m).
    fn recoverable(&self) -> f64 {
        let mut total = 0.0;
        each_group!(self, g => g.add_to(&mut total, |m| m.recoverable_energy()));
        total
    }
}

/// A linear elastic section.
#[derive(Debug, Clone, Copy)]
pub struct ElasticSection {
    pub ea: f64,
    pub eiz: f64,
    pub eiy: f64,
    e: Vector3<f64>,
}

impl ElasticSection {
    /// Errors unless every stiffness is positive and finite.
    pub fn new(ea: f64, eiz: f64, eiy: f64) -> Result<Self, String> {
        for (name, x) in [("EA", ea), ("EIz", eiz), ("EIy", eiy)] {
            if !(x > 0.0 && x.is_finite()) {
                return Err(format!("elastic section: {name} = {x} must be positive"));
            }
        }
        Ok(Self {
            ea,
            eiz,
            eiy,
            e: Vector3::zeros(),
        })
    }

    fn stiffness(&self) -> Matrix3<f64> {
        Matrix3::from_diagonal(&Vector3::new(self.ea, self.eiz, self.eiy))
    }
}

/// A section of either kind.
///
/// # Example
///
/// A symmetric section of four elastic fibers: axial strain gives only `N`, curvature only
/// its moment, and the tangent is `sum E A [1, -y, z]^T [1, -y, z]`.
///
/// ```
/// use mbdbench::model::fiber_column::material::{Elastic, ElasticParams, Material};
/// use mbdbench::model::fiber_column::section::{Fiber, FiberSection, Section};
/// use nalgebra::Vector3;
///
/// let m = Material::Elastic(Elastic::new(ElasticParams { e: 2.0 }).unwrap());
/// let at = |y, z| Fiber { y, z, area: 0.25, material: m };
/// let mut s = Section::Fiber(
///     FiberSection::new(vec![at(1.0, 0.0), at(-1.0, 0.0), at(0.0, 1.0), at(0.0, -1.0)]).unwrap(),
/// );
/// let (force, k) = s.set_trial(&Vector3::new(1e-3, 2e-3, 0.0));
/// assert!((force - Vector3::new(2e-3, 2.0 * 0.5 * 2e-3, 0.0)).norm() < 1e-15);
/// assert_eq!(k[(0, 0)], 2.0);
/// assert_eq!(k[(1, 1)], 1.0);
/// ```
// A handful of sections per element: the fiber variant's size (its per-model arrays) costs
// nothing, and boxing it would add an indirection to the hot loop.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub enum Section {
    Elastic(ElasticSection),
    Fiber(FiberSection),
}

impl Section {
    /// Sets the trial section deformations (from the last committed state); returns the
    /// trial section forces and tangent.
    pub fn set_trial(&mut self, e: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
        match self {
            Section::Elastic(s) => {
                s.e = *e;
                let k = s.stiffness();
                (k * e, k)
            }
            Section::Fiber(s) => s.set_trial(e),
        }
    }

    /// The tangent of the unstrained, virgin section.
    pub fn initial_tangent(&self) -> Matrix3<f64> {
        match self {
            Section::Elastic(s) => s.stiffness(),
            Section::Fiber(s) => s.initial_tangent(),
        }
    }

    /// Commits the trial state.
    pub fn commit(&mut self) {
        if let Section::Fiber(s) = self {
            each_group!(mut s, g => g.commit());
        }
    }

    /// Returns to the last committed state.
    pub fn revert(&mut self) {
        if let Section::Fiber(s) = self {
            each_group!(mut s, g => g.revert());
        }
    }

    /// Work per unit length done on the section along its path (J/m): the fibers' trapezoid
    /// work densities times their areas; for the elastic section its strain energy.
    pub fn work(&self) -> f64 {
        match self {
            Section::Elastic(s) => 0.5 * s.e.dot(&(s.stiffness() * s.e)),
            Section::Fiber(s) => s.work(),
        }
    }

    /// Recoverable strain energy per unit length of the trial state (J/m).
    pub fn recoverable(&self) -> f64 {
        match self {
            Section::Elastic(s) => 0.5 * s.e.dot(&(s.stiffness() * s.e)),
            Section::Fiber(s) => s.recoverable(),
        }
    }
}
