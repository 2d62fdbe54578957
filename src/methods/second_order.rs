//! The method face for second-order structural systems (`structural::SecondOrder`: `M a + C v
//! + f_int(q) = f_ext(t)` with its tangent): a structural integrator written once, as a
//! factory over such systems, runs on every family form that is one (the flexible beam's
//! `fe_exact`, `modal_stiffened` and `modal_linear`), monomorphised per system.
//!
//! [`SecondOrderMethod`] names, for every `S: SecondOrder`, the method type `On<S>` (a
//! `structural::method::Method<S>`: the consistent start and the step, with its Newton
//! iteration) and builds a fresh one per run. The built-in Newmark (average acceleration,
//! order 2), HHT-alpha (Hilber, Hughes & Taylor 1977, alpha = -0.05) and generalized-alpha
//! (Chung & Hulbert 1993, rho_inf = 0.9) are their own factories (one value serves every
//! system) and reach the families through the one list [`each`], the path a method from outside
//! the crate takes (`catalogue::Catalogue::with_structural_method`).
//!
//! Not covered here: the path-dependent structures (`structural::path_step::Path`, the fiber
//! column's dynamic scene), whose built-in schemes the column still builds itself, and the
//! constrained index-3 form (`gen_alpha_i3` on `structural::Constraints`).
//!
//! # Example
//!
//! ```
//! use mbdbench::methods::second_order::{each, SecondOrderMethod, VisitSecondOrder};
//! struct Names(Vec<&'static str>);
//! impl VisitSecondOrder for Names {
//!     fn method<M: SecondOrderMethod>(&mut self, name: &'static str, _m: M) {
//!         self.0.push(name);
//!     }
//! }
//! let mut n = Names(vec![]);
//! each(&mut n);
//! assert_eq!(n.0, ["newmark", "hht", "gen_alpha"]);
//! ```
use crate::structural::SecondOrder;
use crate::structural::gen_alpha::GenAlpha;
use crate::structural::hht::Hht;
use crate::structural::method::Method;
use crate::structural::newmark::Newmark;
use crate::structural::newton::NewtonOptions;

/// A structural method written once for every second-order system.
pub trait SecondOrderMethod: Send + Sync + 'static {
    /// The method on systems of type `S`.
    type On<S: SecondOrder>: Method<S>;
    /// A fresh method for a run on a system of type `S`.
    fn on<S: SecondOrder>(&self) -> Self::On<S>;
}

/// A built-in method that is its own factory: one value, cloned for each run.
macro_rules! own_factory {
    ($($ty:ty),*) => {
        $(
            impl SecondOrderMethod for $ty {
                type On<S: SecondOrder> = $ty;
                fn on<S: SecondOrder>(&self) -> $ty {
                    self.clone()
                }
            }
        )*
    };
}

own_factory!(Newmark, Hht, GenAlpha);

/// A shared method is the method: a catalogue hands one registered method to every family.
impl<M: SecondOrderMethod> SecondOrderMethod for std::sync::Arc<M> {
    type On<S: SecondOrder> = M::On<S>;
    fn on<S: SecondOrder>(&self) -> M::On<S> {
        (**self).on::<S>()
    }
}

/// What instantiates structural methods: a family building its variants visits every method
/// of a list ([`each`]).
pub trait VisitSecondOrder {
    /// One method: `name` is the name its records carry (the integrator axis).
    fn method<M: SecondOrderMethod>(&mut self, name: &'static str, m: M);
}

/// Hands every built-in structural method to `v`, in the integrators' report order, with the
/// suite's settings: Newmark's average acceleration, HHT at alpha = -0.05, generalized-alpha
/// at rho_inf = 0.9, each with the default Newton options.
pub fn each(v: &mut impl VisitSecondOrder) {
    let newmark = Newmark::new(NewtonOptions::default()).expect("valid defaults");
    v.method("newmark", newmark);
    v.method("hht", Hht::default());
    v.method("gen_alpha", GenAlpha::default());
}
