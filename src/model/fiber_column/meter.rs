//! A run's budgets as the fiber column spends them (cases/README.md, "Budgets"): every state
//! determination (one per Newton iteration, one to close a step, one per equilibrium check)
//! and every force-based element iteration counts one against `max_rhs_evals`, and the work
//! units of `estimate::Mesh` (a Newton iteration's dense pass, an element iteration's
//! sections) count against `max_work`. A Newton loop or an element's iterations that would
//! pass either stop with a typed `work_limit` naming the key: the Newton and element
//! iteration limits (`numerics.max_iter`, `element_max_iter`) bound a step, the meter bounds
//! the run, so a tolerance no step can meet ends the run in about the time the budget allows
//! instead of hours.
//!
//! The meter only counts; it changes no iterate. The counts it keeps are its own (the
//! summary's `rhs_evals` still counts a step's Newton iterations plus one).
//!
//! # Example
//!
//! ```
//! use mbdbench::model::fiber_column::estimate::Mesh;
//! use mbdbench::model::fiber_column::meter::Meter;
//!
//! let mesh = Mesh { count: 1.0, points: 5.0, fibers: 90.0, force: true };
//! let mut m = Meter::new(10, u64::MAX, &mesh);
//! assert!(m.assembly().is_ok() && m.newton().is_ok());
//! assert_eq!(m.element_allowance(), 9);
//! assert!(m.elements(9, true).is_ok());
//! assert!(m.assembly().unwrap_err().to_string().contains("max_rhs_evals = 10"));
//! ```
use super::estimate::Mesh;
use crate::structural::path::PathFailure;

/// What a run may still spend, and what each unit of its progress costs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Meter {
    max_evals: u64,
    max_work: u64,
    evals: u64,
    work: f64,
    /// Work units of a Newton iteration's dense pass.
    dense: f64,
    /// Work units of an element iteration (a displacement-based element's update).
    element: f64,
}

impl Meter {
    /// No budget (a column built outside a run: the tests, the equilibrium checks).
    pub fn unlimited() -> Self {
        Meter {
            max_evals: u64::MAX,
            max_work: u64::MAX,
            evals: 0,
            work: 0.0,
            dense: 0.0,
            element: 0.0,
        }
    }

    /// A run's meter for a column of `mesh`, with the case's `max_rhs_evals` and `max_work`.
    pub fn new(max_rhs_evals: u64, max_work: u64, mesh: &Mesh) -> Self {
        let (dense, _) = mesh.iteration_work();
        Meter {
            max_evals: max_rhs_evals,
            max_work,
            evals: 0,
            work: 0.0,
            dense,
            element: mesh.element_iteration_work(),
        }
    }

    /// The failure naming `max_rhs_evals` (`evals`) or `max_work`.
    fn limit(&self, evals: bool) -> PathFailure {
        PathFailure::WorkLimit(if evals {
            format!(
                "more than max_rhs_evals = {} state determinations and element iterations \
                 (cases/README.md, \"Budgets\")",
                self.max_evals
            )
        } else {
            format!(
                "more than max_work = {:.2e} work units (cases/README.md, \"Budgets\")",
                self.max_work as f64
            )
        })
    }

    fn over(&self) -> Option<PathFailure> {
        if self.evals > self.max_evals {
            Some(self.limit(true))
        } else if self.work > self.max_work as f64 {
            Some(self.limit(false))
        } else {
            None
        }
    }

    /// Charges a Newton iteration's dense pass (its factor and solve); the failure when the
    /// run's budget does not cover it.
    pub fn newton(&mut self) -> Result<(), PathFailure> {
        self.work += self.dense;
        self.over().map_or(Ok(()), Err)
    }

    /// Charges a state determination (an assembly: of a Newton iteration, of a step's
    /// closing state, of an equilibrium check); its elements' iterations are charged apart.
    pub fn assembly(&mut self) -> Result<(), PathFailure> {
        self.evals = self.evals.saturating_add(1);
        self.over().map_or(Ok(()), Err)
    }

    /// The element iterations the run's budget still covers: (by `max_rhs_evals`, by
    /// `max_work`).
    fn allowances(&self) -> (u64, u64) {
        let by_evals = self.max_evals.saturating_sub(self.evals);
        let left = self.max_work as f64 - self.work;
        let by_work = if self.element > 0.0 {
            (left / self.element).max(0.0) as u64
        } else {
            u64::MAX
        };
        (by_evals, by_work)
    }

    /// The element iterations the run's budget still covers.
    pub fn element_allowance(&self) -> u64 {
        let (by_evals, by_work) = self.allowances();
        by_evals.min(by_work)
    }

    /// Charges `n` element iterations, against `max_rhs_evals` too when `evals` (a
    /// force-based element's; a displacement-based element's update is part of its state
    /// determination and costs work only).
    pub fn elements(&mut self, n: u64, evals: bool) -> Result<(), PathFailure> {
        if evals {
            self.evals = self.evals.saturating_add(n);
        }
        self.work += n as f64 * self.element;
        self.over().map_or(Ok(()), Err)
    }

    /// The failure of an element stopped by [`Meter::element_allowance`]: the budget whose
    /// allowance ran out.
    pub fn spent(&self) -> PathFailure {
        self.over().unwrap_or_else(|| {
            let (by_evals, by_work) = self.allowances();
            self.limit(by_evals <= by_work)
        })
    }
}
