//! Physical models. Each model family is a folder here, plugged into the suite by one line of
//! the `families!` list below, which declares its module and its entry in the family table
//! (`catalogue::FAMILIES`, in report order).

/// Declares each family's module and the family table from one list of folder names (each
/// folder has `family::FAMILY`); an attribute on a line (a `cfg`) applies to both.
macro_rules! families {
    ($( $(#[$m:meta])* $name:ident ),* $(,)?) => {
        $( $(#[$m])* pub mod $name; )*
        /// The model families, in report order.
        pub static FAMILIES: &[&crate::problem::Family] = &[
            $( $(#[$m])* &$name::family::FAMILY, )*
        ];
    };
}

families! {
    rigid_body,
    flexible_beam,
    fiber_column,
    #[cfg(any(test, feature = "seam-test"))]
    spring_chain,
}
