//! Physical models. Each model family is a folder here, plugged into the suite by one line of
//! the `families!` list below, which declares its module and its entry in the family table
//! (`catalogue::FAMILIES`, in report order).

/// Declares each family's module and the family table from one list of folder names (each
/// folder has `family::FAMILY`); an attribute on a line (a `cfg`) applies to both. A family
/// marked `[ode]` offers first-order systems to every method of the method face
/// (`crate::methods`): its `family::ode_variants` instantiates one method on each of them.
macro_rules! families {
    ($( $(#[$m:meta])* $name:ident $([$ode:ident])? ),* $(,)?) => {
        $( $(#[$m])* pub mod $name; )*
        /// The model families, in report order.
        pub static FAMILIES: &[&crate::problem::Family] = &[
            $( $(#[$m])* &$name::family::FAMILY, )*
        ];
        /// The variants of method `m` (listed as `name`, applying `at`) on the systems of every
        /// family that offers first-order systems: `(model, variants)` per such family, each
        /// variant numbered from 0 in its family's order.
        pub fn ode_variants<M: crate::methods::OdeMethod + Clone>(
            name: &'static str,
            at: crate::methods::Where,
            m: &M,
        ) -> Vec<(&'static str, Vec<crate::problem::Variant>)> {
            let mut out = vec![];
            $( $(#[$m])* {
                $(
                    let _ = stringify!($ode);
                    out.push((
                        $name::family::FAMILY.model,
                        $name::family::ode_variants(name, at, m.clone()),
                    ));
                )?
            } )*
            let _ = (name, at, m);
            out
        }
    };
}

families! {
    rigid_body [ode],
    flexible_beam [ode],
    fiber_column,
    #[cfg(any(test, feature = "seam-test"))]
    spring_chain,
}
