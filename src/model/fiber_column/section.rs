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
//! Where it fails: a section whose fibers all lie on one line through the centroid has a
//! singular `k_s` (no stiffness about that line); `FiberSection::new` refuses a section with
//! no fiber or a non-positive area, and the case loader checks the fibers lie in the section.
use nalgebra::{Matrix3, Vector3};

use super::material::{Material, Uniaxial};

/// One fiber: position in the section (local y, z), area, material with its state.
#[derive(Debug, Clone)]
pub struct Fiber {
    pub y: f64,
    pub z: f64,
    pub area: f64,
    pub material: Material,
}

/// A section of uniaxial fibers.
#[derive(Debug, Clone)]
pub struct FiberSection {
    fibers: Vec<Fiber>,
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
        Ok(Self { fibers })
    }

    /// The fibers.
    pub fn fibers(&self) -> &[Fiber] {
        &self.fibers
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
            Section::Fiber(s) => {
                // The six distinct entries of the symmetric tangent, summed as scalars.
                let (mut n, mut mz, mut my) = (0.0, 0.0, 0.0);
                let [mut k00, mut k01, mut k02, mut k11, mut k12, mut k22] = [0.0; 6];
                for f in &mut s.fibers {
                    let (y, z) = (-f.y, f.z);
                    let (sigma, et) = f.material.set_trial_strain(e.x + y * e.y + z * e.z);
                    let (fa, ka) = (sigma * f.area, et * f.area);
                    n += fa;
                    mz += y * fa;
                    my += z * fa;
                    k00 += ka;
                    k01 += y * ka;
                    k02 += z * ka;
                    k11 += y * y * ka;
                    k12 += y * z * ka;
                    k22 += z * z * ka;
                }
                let k = Matrix3::new(k00, k01, k02, k01, k11, k12, k02, k12, k22);
                (Vector3::new(n, mz, my), k)
            }
        }
    }

    /// The tangent of the unstrained, virgin section.
    pub fn initial_tangent(&self) -> Matrix3<f64> {
        match self {
            Section::Elastic(s) => s.stiffness(),
            Section::Fiber(s) => {
                let mut k = Matrix3::zeros();
                for f in &s.fibers {
                    let a = Vector3::new(1.0, -f.y, f.z);
                    k += a * a.transpose() * (f.material.initial_tangent() * f.area);
                }
                k
            }
        }
    }

    /// Commits the trial state.
    pub fn commit(&mut self) {
        if let Section::Fiber(s) = self {
            for f in &mut s.fibers {
                f.material.commit();
            }
        }
    }

    /// Returns to the last committed state.
    pub fn revert(&mut self) {
        if let Section::Fiber(s) = self {
            for f in &mut s.fibers {
                f.material.revert_to_last_commit();
            }
        }
    }

    /// Work per unit length done on the section along its path (J/m): the fibers' trapezoid
    /// work densities times their areas; for the elastic section its strain energy.
    pub fn work(&self) -> f64 {
        match self {
            Section::Elastic(s) => 0.5 * s.e.dot(&(s.stiffness() * s.e)),
            Section::Fiber(s) => s.fibers.iter().map(|f| f.area * f.material.work()).sum(),
        }
    }

    /// Recoverable strain energy per unit length of the trial state (J/m).
    pub fn recoverable(&self) -> f64 {
        match self {
            Section::Elastic(s) => 0.5 * s.e.dot(&(s.stiffness() * s.e)),
            Section::Fiber(s) => s
                .fibers
                .iter()
                .map(|f| f.area * f.material.recoverable_energy())
                .sum(),
        }
    }
}
