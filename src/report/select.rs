//! Which variants a plot draws. A scene has up to ~150 variants; one plot with all of them is
//! unreadable, so every plot draws one of three fixed selections, named in its caption:
//!
//! - `Rk4`: rk4 on every parameterization (classical RK4 on additive charts, RKMK4 on the
//!   Lie-group charts), both formulations: the parameterizations compared at equal method;
//! - `Adaptive`: every adaptive method (dopri5, dop853) on every parameterization, both
//!   formulations: error against cost over the tolerance ladder;
//! - `So3`: every integrator on the `so3` chart, both formulations: the integrators compared
//!   at equal chart (the only chart on which the geometric methods run).
//!
//! Together they cover the requirement (every parameterization with rk4 and the
//! adaptive methods over the whole ladder) and every registered integrator.
use super::data::VariantRuns;

/// A fixed selection of variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    Rk4,
    Adaptive,
    So3,
}

impl Selection {
    /// All selections, in report order.
    pub const ALL: [Selection; 3] = [Selection::Rk4, Selection::Adaptive, Selection::So3];

    /// A short id for file names.
    pub fn id(self) -> &'static str {
        match self {
            Selection::Rk4 => "rk4",
            Selection::Adaptive => "adaptive",
            Selection::So3 => "so3",
        }
    }

    /// A short title fragment.
    pub fn short(self) -> &'static str {
        match self {
            Selection::Rk4 => "rk4, every chart",
            Selection::Adaptive => "adaptive, every chart",
            Selection::So3 => "so3, every integrator",
        }
    }

    /// The caption sentence naming the lines.
    pub fn describe(self) -> &'static str {
        match self {
            Selection::Rk4 => {
                "Lines: rk4 (classical RK4 on additive charts, RKMK4 on Lie-group charts) on \
                 every parameterization that ran, body formulation solid, spatial dashed."
            }
            Selection::Adaptive => {
                "Lines: every adaptive method (dopri5, dop853) on every parameterization that \
                 ran, over its tolerance ladder; body formulation solid, spatial dashed."
            }
            Selection::So3 => {
                "Lines: every integrator on the so3 chart (unit quaternion on SO(3)), body \
                 formulation solid, spatial dashed (the geometric methods run in the body \
                 formulation only)."
            }
        }
    }

    /// Whether a variant is drawn.
    pub fn admits(self, v: &VariantRuns) -> bool {
        match self {
            Selection::Rk4 => v.key.integrator == "rk4",
            Selection::Adaptive => v.adaptive,
            Selection::So3 => v.key.param == "so3",
        }
    }
}
