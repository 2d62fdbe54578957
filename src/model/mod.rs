//! Physical models. Each model family is a folder here, plugged into the suite by one line of
//! the `families!` list below, which declares its module and its entry in the family table
//! (`catalogue::FAMILIES`, in report order).

/// Declares each family's module and the family table from one list of folder names (each
/// folder has `family::FAMILY`, and `family::Systems`, its `problem::Instantiate`: what it makes
/// of a method registered from outside the crate); an attribute on a line (a `cfg`) applies to
/// all of them.
macro_rules! families {
    ($( $(#[$m:meta])* $name:ident ),* $(,)?) => {
        $( $(#[$m])* pub mod $name; )*
        /// The model families, in report order.
        pub static FAMILIES: &[&crate::problem::Family] = &[
            $( $(#[$m])* &$name::family::FAMILY, )*
        ];
        /// The variants of the first-order method `m` (listed as `name`, applying `at`) on
        /// every family's first-order systems: `(model, variants)` per family, each family's
        /// numbered from 0 in its order (none for a family without such systems).
        pub fn ode_variants<M: crate::methods::OdeMethod + Clone>(
            name: &'static str,
            at: crate::methods::Where,
            m: &M,
        ) -> Vec<(&'static str, Vec<crate::problem::Variant>)> {
            use crate::problem::Instantiate;
            let mut out = vec![];
            $( $(#[$m])* {
                out.push(($name::family::FAMILY.model, $name::family::Systems::ode(name, at, m.clone())));
            } )*
            out
        }
        /// The variants of the structural method `m` (listed as `name`) on every family's
        /// second-order systems, as [`ode_variants`].
        pub fn second_order_variants<M: crate::methods::second_order::SecondOrderMethod + Clone>(
            name: &'static str,
            m: &M,
        ) -> Vec<(&'static str, Vec<crate::problem::Variant>)> {
            use crate::problem::Instantiate;
            let mut out = vec![];
            $( $(#[$m])* {
                out.push((
                    $name::family::FAMILY.model,
                    $name::family::Systems::second_order(name, m.clone()),
                ));
            } )*
            out
        }
    };
}

families! {
    rigid_body,
    flexible_beam,
    fiber_column,
    #[cfg(any(test, feature = "seam-test"))]
    spring_chain,
}
