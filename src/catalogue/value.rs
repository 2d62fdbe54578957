//! The catalogue as a value: the families a run is made with, the methods registered from
//! outside the crate, and where the case files and references are. [`Catalogue::builtin`] is
//! the catalogue the command line uses (the family table, the embedded cases); a library user
//! extends it: [`Catalogue::with_method`] registers a first-order method written once through
//! the method face (`crate::methods`) on every family that offers first-order systems (the
//! rigid body's charts and formulations, the flexible beam's ODE forms), through the same
//! instantiation the built-in methods take (`model::ode_variants`, the family's
//! `family::ode_variants`, monomorphised per system); [`Catalogue::with_cases`] and
//! [`Catalogue::with_references`] point it at the user's folders;
//! [`Catalogue::with_structural_method`] registers a structural method written once for every
//! second-order system (`methods::second_order`), on the beam's structural forms.
//!
//! A registered method extends each family it applies to: the catalogue holds its own copy of
//! the family (`problem::Variants::Extended`, the family's table plus the new variants, and the
//! new name appended to its integrator axis), and the problems it compiles
//! ([`Catalogue::problems`]) are bound to that copy, so everything downstream of a problem (the
//! variant matrix, the ladders, the records) sees the method as it sees a built-in. The copies
//! live as long as the process (one per registration, the size of the family's table).
//!
//! Refused, with a [`RegisterError`] naming the method: a name already registered (a built-in
//! integrator of any family, or an earlier registration), a name that is not a lower-case
//! identifier (it appears in file names and on the command line), and a method that applies
//! to no system of the catalogue.
//!
//! # Example
//!
//! ```
//! use mbdbench::catalogue::Catalogue;
//! use mbdbench::methods::{builtin::Rk4, Fixed, Where};
//!
//! // RK4 again under another name: every rigid chart and formulation, every beam ODE form.
//! let cat = Catalogue::builtin().with_method("my_rk4", Where::Everywhere, Fixed(Rk4)).unwrap();
//! let rigid = cat.find_family("rigid_body").unwrap();
//! assert!(rigid.find("so3", "my_rk4", "spatial").is_some());
//! assert!(rigid.axes.integrators.contains(&"my_rk4"));
//! // A name already taken is refused.
//! let again = cat.with_method("rk4", Where::Everywhere, Fixed(Rk4));
//! assert!(again.unwrap_err().to_string().contains("already registered"));
//! ```
use std::path::{Path, PathBuf};

use crate::case::{Case, CaseError};
use crate::methods::second_order::SecondOrderMethod;
use crate::methods::{OdeMethod, Where};
use crate::problem::{Axes, Family, Problem, Variant, Variants};

/// A method the catalogue refused to register.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RegisterError {
    /// The integrator name it was to be registered under.
    pub name: String,
    pub message: String,
}

impl std::fmt::Display for RegisterError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "method `{}`: {}", self.name, self.message)
    }
}

impl std::error::Error for RegisterError {}

/// The families, registered methods, cases and references a run is made with.
#[derive(Debug, Clone)]
pub struct Catalogue {
    families: Vec<&'static Family>,
    /// The methods registered from outside, in registration order.
    registered: Vec<&'static str>,
    /// The case folder; `None`: the cases compiled into the crate.
    cases: Option<PathBuf>,
    /// The references folder; `None`: the caller's default.
    references: Option<PathBuf>,
}

impl Catalogue {
    /// The built-in catalogue: the family table (`model::FAMILIES`), no registered method, the
    /// embedded cases.
    pub fn builtin() -> Catalogue {
        Catalogue {
            families: crate::model::FAMILIES.to_vec(),
            registered: vec![],
            cases: None,
            references: None,
        }
    }

    /// Registers the first-order method `m` under `name` on every system of every family where
    /// it applies (`at`).
    pub fn with_method<M: OdeMethod>(
        self,
        name: &'static str,
        at: Where,
        m: M,
    ) -> Result<Catalogue, RegisterError> {
        self.check_name(name)?;
        let m = std::sync::Arc::new(m);
        let variants = crate::model::ode_variants(name, at, &m);
        self.register(name, variants)
    }

    /// Registers the structural method `m` under `name` on every second-order system of every
    /// family (the flexible beam's `fe_exact`, `modal_stiffened` and `modal_linear`).
    pub fn with_structural_method<M: SecondOrderMethod>(
        self,
        name: &'static str,
        m: M,
    ) -> Result<Catalogue, RegisterError> {
        self.check_name(name)?;
        let m = std::sync::Arc::new(m);
        let variants = crate::model::second_order_variants(name, &m);
        self.register(name, variants)
    }

    /// Refuses a name that is not a lower-case identifier or is taken.
    fn check_name(&self, name: &'static str) -> Result<(), RegisterError> {
        let refuse = |message: String| RegisterError {
            name: name.into(),
            message,
        };
        if name.is_empty()
            || !name.starts_with(|c: char| c.is_ascii_lowercase())
            || !name
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        {
            return Err(refuse(
                "not a lower-case identifier ([a-z][a-z0-9_]*): the name is written in file \
                 names and on the command line"
                    .into(),
            ));
        }
        let taken = |f: &&&Family| {
            f.axes.integrators.contains(&name) || f.variants().iter().any(|v| v.integrator == name)
        };
        match self.families.iter().find(taken) {
            Some(f) => Err(refuse(format!(
                "already registered in the family `{}`{}",
                f.model,
                if self.registered.contains(&name) {
                    " (by an earlier registration)"
                } else {
                    " (a built-in integrator)"
                }
            ))),
            None => Ok(()),
        }
    }

    /// Extends each family by its variants of the method `name`; refused when there are none.
    fn register(
        mut self,
        name: &'static str,
        variants: Vec<(&'static str, Vec<Variant>)>,
    ) -> Result<Catalogue, RegisterError> {
        let mut added = 0;
        for (model, variants) in variants {
            if variants.is_empty() {
                continue;
            }
            if let Some(i) = self.families.iter().position(|f| f.model == model) {
                added += variants.len();
                self.families[i] = extended(self.families[i], name, variants);
            }
        }
        if added == 0 {
            return Err(RegisterError {
                name: name.into(),
                message: "applies to no system of the catalogue's families".into(),
            });
        }
        self.registered.push(name);
        Ok(self)
    }

    /// Reads the case files from `dir` (every `*.toml`, as `--cases`) instead of the embedded
    /// ones.
    pub fn with_cases(mut self, dir: impl Into<PathBuf>) -> Catalogue {
        self.cases = Some(dir.into());
        self
    }

    /// Reads and checks the references under `dir`.
    pub fn with_references(mut self, dir: impl Into<PathBuf>) -> Catalogue {
        self.references = Some(dir.into());
        self
    }

    /// The families, in report order (the built-in table's, extended by registrations).
    pub fn families(&self) -> &[&'static Family] {
        &self.families
    }

    /// The names of the methods registered from outside, in registration order.
    pub fn registered(&self) -> &[&'static str] {
        &self.registered
    }

    /// The references folder given by `with_references`, if any.
    pub fn references(&self) -> Option<&Path> {
        self.references.as_deref()
    }

    /// The family with `model` key `model`.
    pub fn find_family(&self, model: &str) -> Option<&'static Family> {
        self.families.iter().copied().find(|f| f.model == model)
    }

    /// The family of a case: this catalogue's copy when it has the case's family, else the
    /// built-in table's (`catalogue::family_of`).
    pub fn family_or_builtin(&self, case: &Case) -> &'static Family {
        self.find_family(case.model())
            .unwrap_or_else(|| super::family_of(case))
    }

    /// One scene of a case compiled by its family and bound to this catalogue's copy of it
    /// (whose variants include the registered methods).
    pub fn compile(
        &self,
        case: &Case,
        scene: &crate::case::Scene,
    ) -> Result<Box<dyn Problem>, CaseError> {
        let family = self.family_or_builtin(case);
        let mut p = (family.compile)(case, scene)?;
        p.header_mut().family = family;
        Ok(p)
    }

    /// The names in a variant filter that no family of this catalogue has on that axis (bad
    /// input): `--param NAME`, `--integrator NAME`, `--formulation NAME`.
    pub fn unknown_names(&self, filter: &crate::selection::VariantFilter) -> Vec<String> {
        let fams = &self.families;
        let mut bad = vec![];
        for p in &filter.param {
            if !fams.iter().any(|f| f.axes.params.contains(&p.as_str())) {
                bad.push(format!("--param {p}"));
            }
        }
        for i in &filter.integrator {
            if !fams
                .iter()
                .any(|f| f.variants().iter().any(|v| v.integrator == i))
            {
                bad.push(format!("--integrator {i}"));
            }
        }
        for f in &filter.formulation {
            if !fams
                .iter()
                .any(|x| x.axes.formulations.contains(&f.as_str()))
            {
                bad.push(format!("--formulation {f}"));
            }
        }
        bad
    }

    /// The catalogue's cases: its case folder's, else the embedded ones.
    pub fn cases(&self) -> Result<Vec<Case>, CaseError> {
        match &self.cases {
            Some(dir) => super::load_dir(dir),
            None => super::embedded(),
        }
    }

    /// The compiled problems of the selected cases and scenes, each bound to this catalogue's
    /// copy of its family (so its variants include the registered methods).
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::catalogue::Catalogue;
    /// use mbdbench::methods::{builtin::Cg3, Fixed, Where};
    /// use mbdbench::problem::{Stepping, Want};
    ///
    /// let cat = Catalogue::builtin().with_method("my_cg3", Where::LieGroup, Fixed(Cg3)).unwrap();
    /// let cases = cat.cases().unwrap();
    /// let p = cat.problems(&cases, &["nine_spring".into()], &["two_angles".into()]).unwrap();
    /// let v = p[0].family().find("so3", "my_cg3", "body").unwrap();
    /// let out = p[0].run(v, Stepping::Dt(1e-2), Want::Timing).unwrap();
    /// assert!(out.failure.is_none() && out.stats.steps > 0);
    /// // Not on a chart that is no Lie group.
    /// assert!(p[0].family().find("quat", "my_cg3", "body").is_none());
    /// ```
    pub fn problems(
        &self,
        cases: &[Case],
        case_filter: &[String],
        scene_filter: &[String],
    ) -> Result<Vec<Box<dyn Problem>>, String> {
        crate::case::select(cases, case_filter, scene_filter)?
            .into_iter()
            .map(|(c, s)| self.compile(c, s).map_err(|e| e.to_string()))
            .collect()
    }
}

/// Two catalogues are the same when they hold the same families (the same copies), the same
/// registrations and the same folders.
impl PartialEq for Catalogue {
    fn eq(&self, o: &Catalogue) -> bool {
        self.families.len() == o.families.len()
            && self
                .families
                .iter()
                .zip(&o.families)
                .all(|(a, b)| std::ptr::eq(*a, *b))
            && (&self.registered, &self.cases, &self.references)
                == (&o.registered, &o.cases, &o.references)
    }
}

/// `family` with `variants` of the method `name` appended (numbered on from its table) and
/// `name` appended to its integrator axis: a copy that lives as long as the process.
fn extended(
    family: &'static Family,
    name: &'static str,
    variants: Vec<Variant>,
) -> &'static Family {
    let base = family.variants();
    let mut all = base.to_vec();
    all.extend(variants.into_iter().map(|mut v| {
        v.index += base.len();
        v
    }));
    let mut integrators = family.axes.integrators.to_vec();
    integrators.push(name);
    Box::leak(Box::new(Family {
        variants: Variants::Extended(Box::leak(all.into_boxed_slice())),
        axes: Axes {
            integrators: Box::leak(integrators.into_boxed_slice()),
            ..family.axes
        },
        ..family.clone()
    }))
}

#[cfg(test)]
#[path = "value_tests.rs"]
mod tests;
