//! The trial / committed bookkeeping of the uniaxial models, written once: a [`History`] holds
//! one fiber's trial state, its committed state and the work committed so far, and a model
//! that implements [`Law`] (its trial state from the committed one, its initial tangent and its
//! recoverable energy, and where it keeps its history) is [`Uniaxial`] by the blanket impl
//! here, which is the only place that sets, commits or reverts a state.
//!
//! Invariants: a trial state is [`Law::trial_state`] of the committed state and the strain,
//! never of an earlier trial; `commit` first adds the trial increment's trapezoid to the
//! committed work, then copies the trial state into the committed one; `revert` copies the
//! committed state back into the trial, bit for bit; `work` is the committed work plus the
//! trapezoid from the committed point to the trial point, `W_c + (σ_c + σ)(ε − ε_c)/2`. A state
//! is a `Copy` value (no allocation) of the model's own type; a [`History`] reads of it only
//! its point (strain, stress, tangent), through [`State`].
use super::Uniaxial;

/// A model's state as its [`History`] reads it.
pub(super) trait State: Copy {
    /// The state's point on the stress-strain curve: (strain, stress, tangent).
    fn point(&self) -> (f64, f64, f64);
}

/// The state of a model that needs no history variable beyond its point (the elastic model;
/// Steel01 with isotropic hardening off).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Point {
    pub(super) strain: f64,
    pub(super) stress: f64,
    pub(super) tangent: f64,
}

impl State for Point {
    fn point(&self) -> (f64, f64, f64) {
        (self.strain, self.stress, self.tangent)
    }
}

/// One fiber's trial state, committed state and committed work density (J/m^3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct History<S> {
    trial: S,
    committed: S,
    committed_work: f64,
}

impl<S: State> History<S> {
    /// The history of a virgin fiber: `virgin` both trial and committed, no work.
    pub(super) fn new(virgin: S) -> Self {
        Self {
            trial: virgin,
            committed: virgin,
            committed_work: 0.0,
        }
    }

    /// The trial state.
    pub(super) fn trial(&self) -> &S {
        &self.trial
    }

    /// Makes `trial` the trial state; returns its (stress, tangent).
    #[inline(always)]
    fn set_trial(&mut self, trial: S) -> (f64, f64) {
        self.trial = trial;
        let (_, stress, tangent) = trial.point();
        (stress, tangent)
    }

    /// Adds the trial increment's trapezoid to the committed work, then commits the trial.
    fn commit(&mut self) {
        self.committed_work = self.work();
        self.committed = self.trial;
    }

    /// Makes the committed state the trial one again.
    fn revert(&mut self) {
        self.trial = self.committed;
    }

    /// The committed work plus the trapezoid from the committed point to the trial point.
    fn work(&self) -> f64 {
        let (committed_strain, committed_stress, _) = self.committed.point();
        let (strain, stress, _) = self.trial.point();
        self.committed_work + trapezoid(committed_strain, committed_stress, strain, stress)
    }
}

/// The trapezoid of one strain increment, `(σ_a + σ_b)(ε_b − ε_a)/2`, the unit of
/// [`Uniaxial::work`].
fn trapezoid(strain_a: f64, stress_a: f64, strain_b: f64, stress_b: f64) -> f64 {
    0.5 * (stress_a + stress_b) * (strain_b - strain_a)
}

/// A uniaxial model as its constitutive law and the [`History`] it keeps; the blanket impl
/// below makes it [`Uniaxial`].
pub(super) trait Law {
    /// The model's state: its point and its own history variables.
    type State: State;
    /// The model's history.
    fn history(&self) -> &History<Self::State>;
    /// The model's history, to set, commit and revert.
    fn history_mut(&mut self) -> &mut History<Self::State>;
    /// The trial state at `strain` from the committed state `committed`.
    fn trial_state(&self, committed: Self::State, strain: f64) -> Self::State;
    /// [`Uniaxial::initial_tangent`].
    fn initial_tangent(&self) -> f64;
    /// [`Uniaxial::recoverable_energy`] of the trial state.
    fn recoverable_energy(&self) -> f64;
}

impl<T: Law> Uniaxial for T {
    // Inlined into the section's fiber loop: as a call it made the loop spill its nine
    // running sums to the stack around every fiber (SysV saves no float register), 28 % of
    // a cyclic run in the loop itself.
    #[inline(always)]
    fn set_trial_strain(&mut self, strain: f64) -> (f64, f64) {
        let trial = self.trial_state(self.history().committed, strain);
        self.history_mut().set_trial(trial)
    }
    fn strain(&self) -> f64 {
        self.history().trial.point().0
    }
    fn stress(&self) -> f64 {
        self.history().trial.point().1
    }
    fn tangent(&self) -> f64 {
        self.history().trial.point().2
    }
    fn initial_tangent(&self) -> f64 {
        Law::initial_tangent(self)
    }
    fn commit(&mut self) {
        self.history_mut().commit();
    }
    fn revert_to_last_commit(&mut self) {
        self.history_mut().revert();
    }
    fn work(&self) -> f64 {
        self.history().work()
    }
    fn recoverable_energy(&self) -> f64 {
        Law::recoverable_energy(self)
    }
}
