//! The variant matrix of a family: every combination of its three axes in report order
//! (param, then integrator, then formulation), each either a registered variant or `n/a`
//! with the family's reason. The one enumeration of the variant space: the suite, `list`, the
//! gate, the stability study and the benches iterate it instead of nesting the axes by hand.
//!
//! # Example
//!
//! ```
//! use mbdbench::catalogue;
//! use mbdbench::problem::{self, Entry};
//!
//! let family = catalogue::FAMILIES[0];
//! let cells: Vec<_> = problem::matrix(family).collect();
//! let n = family.axes.params.len() * family.axes.integrators.len() * family.axes.formulations.len();
//! assert_eq!(cells.len(), n);
//! let registered = cells.iter().filter(|c| matches!(c.entry, Entry::Registered(_))).count();
//! assert_eq!(registered, family.variants().len());
//! ```
use super::{Family, Variant};

/// A registered variant, or why the combination is not applicable.
#[derive(Debug, Clone, PartialEq)]
pub enum Entry {
    Registered(&'static Variant),
    NotApplicable(String),
}

/// One combination of the three axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    pub param: &'static str,
    pub integrator: &'static str,
    pub formulation: &'static str,
    pub entry: Entry,
}

/// Every combination of `family`'s axes in report order.
pub fn matrix(family: &'static Family) -> impl Iterator<Item = Cell> {
    let a = family.axes;
    a.params.iter().flat_map(move |&param| {
        a.integrators.iter().flat_map(move |&integrator| {
            a.formulations.iter().map(move |&formulation| Cell {
                param,
                integrator,
                formulation,
                entry: match family.find(param, integrator, formulation) {
                    Some(v) => Entry::Registered(v),
                    None => Entry::NotApplicable((family.static_na_reason)(
                        param,
                        integrator,
                        formulation,
                    )),
                },
            })
        })
    })
}

/// The registered variants of a family, in report order.
pub fn registered(family: &'static Family) -> impl Iterator<Item = &'static Variant> {
    matrix(family).filter_map(|c| match c.entry {
        Entry::Registered(v) => Some(v),
        Entry::NotApplicable(_) => None,
    })
}
