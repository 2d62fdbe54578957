//! What a `run` (or `stability`) was asked to compute, recorded in its summary as
//! `selection`: the tier (`quick` or `full`), the `--case`, `--scene`, `--param`,
//! `--integrator` and `--formulation` filters (an empty list selects every name) and a
//! `--t-end` override. Readers use it instead of guessing from the records:
//!
//! - `gate` and the report skip (and say so) the gated points that lie outside the run's
//!   selection, and know the summary's tier without inferring it from its ladder points;
//!   a point inside the selection without a record still fails (a run that lost a case
//!   cannot pass by omission);
//! - a filtered `run` into a folder that holds a broader summary merges into it when the old
//!   selection covers the new one (`covers`) and both come from the same commit and tier
//!   without a `--t-end`, replacing exactly the records the new run selects (`admits`).
//!
//! Summaries written before the field existed have no selection: readers then treat them as
//! selecting everything, of the tier their ladder points show.
//!
//! # Example
//!
//! ```
//! use mbdbench::selection::{Selection, Tier};
//! use mbdbench::summary::RunKey;
//!
//! let all = Selection::everything(Tier::Full);
//! let mut one = Selection::everything(Tier::Full);
//! one.cases = vec!["nine_spring".into()];
//! assert!(all.covers(&one) && !one.covers(&all));
//! let k = RunKey::new("gimbal_lock", "tumble", "so3", "rk4", "body");
//! assert!(all.admits(&k) && !one.admits(&k));
//! assert_eq!(one.flags(), "--case nine_spring");
//! ```
use serde::{Deserialize, Serialize};

/// The ladder tier of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Tier {
    /// `--quick`: the cases' quick ladders.
    Quick,
    /// The full ladders.
    Full,
}

impl Tier {
    /// `quick` or `full`.
    pub fn name(self) -> &'static str {
        match self {
            Tier::Quick => "quick",
            Tier::Full => "full",
        }
    }

    /// The tier of `--quick`.
    pub fn of(quick: bool) -> Tier {
        if quick { Tier::Quick } else { Tier::Full }
    }
}

/// A run's selection (an empty list: every name).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Selection {
    pub tier: Tier,
    #[serde(default)]
    pub cases: Vec<String>,
    #[serde(default)]
    pub scenes: Vec<String>,
    #[serde(default)]
    pub params: Vec<String>,
    #[serde(default)]
    pub integrators: Vec<String>,
    #[serde(default)]
    pub formulations: Vec<String>,
    /// `--t-end`: every scene's horizon overridden (errors against references then absent).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_end: Option<f64>,
}

/// The most names one filter of a selection read from a file may list.
pub const MAX_NAMES: usize = 256;

/// The longest name a selection read from a file may hold (bytes).
pub const MAX_NAME_LEN: usize = 128;

/// A run's names on the five things a selection filters, in this order: case, scene, param,
/// integrator, formulation (`summary::RunKey` implements it; `selection` sits below
/// `summary`, whose files record their selection).
pub trait RunNames {
    fn run_names(&self) -> [&str; 5];
}

fn keep(list: &[String], name: &str) -> bool {
    list.is_empty() || list.iter().any(|x| x == name)
}

/// Whether the filter `wide` selects every name `narrow` selects.
fn wider(wide: &[String], narrow: &[String]) -> bool {
    wide.is_empty() || (!narrow.is_empty() && narrow.iter().all(|n| wide.contains(n)))
}

impl Selection {
    /// Every case, scene and variant of a tier.
    pub fn everything(tier: Tier) -> Selection {
        Selection {
            tier,
            cases: vec![],
            scenes: vec![],
            params: vec![],
            integrators: vec![],
            formulations: vec![],
            t_end: None,
        }
    }

    /// Whether a run of this key is selected (its ladder point is the tier's business).
    pub fn admits(&self, k: &impl RunNames) -> bool {
        let [case, scene, param, integrator, formulation] = k.run_names();
        keep(&self.cases, case)
            && keep(&self.scenes, scene)
            && keep(&self.params, param)
            && keep(&self.integrators, integrator)
            && keep(&self.formulations, formulation)
    }

    /// Whether this selection holds every run `other` selects, at the same tier and horizon.
    pub fn covers(&self, other: &Selection) -> bool {
        self.tier == other.tier
            && self.t_end == other.t_end
            && wider(&self.cases, &other.cases)
            && wider(&self.scenes, &other.scenes)
            && wider(&self.params, &other.params)
            && wider(&self.integrators, &other.integrators)
            && wider(&self.formulations, &other.formulations)
    }

    /// The selection with each filter's repeated names removed (first one kept): a command
    /// line may name a case twice, a file must not (`check`).
    pub fn deduped(mut self) -> Selection {
        for list in [
            &mut self.cases,
            &mut self.scenes,
            &mut self.params,
            &mut self.integrators,
            &mut self.formulations,
        ] {
            let mut seen: Vec<String> = Vec::with_capacity(list.len());
            list.retain(|n| {
                let new = !seen.contains(n);
                if new {
                    seen.push(n.clone());
                }
                new
            });
        }
        self
    }

    /// Checks a selection read from a file: each filter names every name once, at most
    /// [`MAX_NAMES`] names, each 1 to [`MAX_NAME_LEN`] bytes without control characters (as a
    /// record's names: the outputs escape them; a command line gives a few), and `t_end` is
    /// finite and
    /// positive. Its flags go into the notes of skipped gate rows and the page, so an
    /// unchecked file could multiply a megabyte of names into every row.
    pub fn check(&self) -> Result<(), String> {
        for (key, list) in [
            ("cases", &self.cases),
            ("scenes", &self.scenes),
            ("params", &self.params),
            ("integrators", &self.integrators),
            ("formulations", &self.formulations),
        ] {
            if list.len() > MAX_NAMES {
                return Err(format!(
                    "key `selection.{key}` lists {} names (at most {MAX_NAMES})",
                    list.len()
                ));
            }
            for (i, n) in list.iter().enumerate() {
                let ok =
                    !n.is_empty() && n.len() <= MAX_NAME_LEN && !n.chars().any(char::is_control);
                if !ok {
                    return Err(format!(
                        "key `selection.{key}[{i}]` is not a name (1 to {MAX_NAME_LEN} bytes, \
                         no control characters)"
                    ));
                }
                if list[..i].contains(n) {
                    return Err(format!("key `selection.{key}[{i}]` repeats `{n}`"));
                }
            }
        }
        if let Some(t) = self.t_end
            && !(t.is_finite() && t > 0.0)
        {
            return Err(format!("key `selection.t_end` is {t}, not a positive time"));
        }
        Ok(())
    }

    /// Whether nothing is filtered out.
    pub fn is_everything(&self) -> bool {
        self.filters().is_empty() && self.t_end.is_none()
    }

    fn filters(&self) -> Vec<(&'static str, &[String])> {
        [
            ("--case", &self.cases[..]),
            ("--scene", &self.scenes[..]),
            ("--param", &self.params[..]),
            ("--integrator", &self.integrators[..]),
            ("--formulation", &self.formulations[..]),
        ]
        .into_iter()
        .filter(|(_, l)| !l.is_empty())
        .collect()
    }

    /// The filters as command-line flags (`--case nine_spring --param so3`), or `""`.
    pub fn flags(&self) -> String {
        let mut parts: Vec<String> = self
            .filters()
            .into_iter()
            .flat_map(|(flag, l)| l.iter().map(move |n| format!("{flag} {n}")))
            .collect();
        if let Some(t) = self.t_end {
            parts.push(format!("--t-end {t}"));
        }
        parts.join(" ")
    }

    /// A file-name-safe slug of the filters (`nine_spring-so3`), `""` for everything.
    pub fn slug(&self) -> String {
        let mut parts: Vec<String> = self
            .filters()
            .into_iter()
            .flat_map(|(_, l)| l.iter().cloned())
            .collect();
        if let Some(t) = self.t_end {
            parts.push(format!("t{t}"));
        }
        parts
            .join("-")
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.' {
                    c
                } else {
                    '_'
                }
            })
            .take(80)
            .collect()
    }
}

/// Variant filters (empty = all).
#[derive(Debug, Clone, Default)]
pub struct VariantFilter {
    pub param: Vec<String>,
    pub integrator: Vec<String>,
    pub formulation: Vec<String>,
}

impl VariantFilter {
    fn keep(list: &[String], v: &str) -> bool {
        list.is_empty() || list.iter().any(|x| x == v)
    }
    /// Whether a combination passes.
    pub fn admits(&self, param: &str, integrator: &str, formulation: &str) -> bool {
        Self::keep(&self.param, param)
            && Self::keep(&self.integrator, integrator)
            && Self::keep(&self.formulation, formulation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sel(cases: &[&str], params: &[&str]) -> Selection {
        let mut s = Selection::everything(Tier::Quick);
        s.cases = cases.iter().map(|x| x.to_string()).collect();
        s.params = params.iter().map(|x| x.to_string()).collect();
        s
    }

    /// `covers` is the subset order of the selected runs: reflexive, everything covers any
    /// filter of its tier, a filter never covers a wider one, and tiers or horizons never mix.
    #[test]
    fn covers_is_the_subset_order() {
        let all = Selection::everything(Tier::Quick);
        let a = sel(&["nine_spring"], &[]);
        let ab = sel(&["nine_spring", "free_body"], &[]);
        let a_so3 = sel(&["nine_spring"], &["so3"]);
        for s in [&all, &a, &ab, &a_so3] {
            assert!(s.covers(s));
            assert!(all.covers(s));
        }
        assert!(ab.covers(&a) && !a.covers(&ab));
        assert!(a.covers(&a_so3) && !a_so3.covers(&a));
        assert!(!a.covers(&sel(&["free_body"], &[])));
        assert!(!Selection::everything(Tier::Full).covers(&all));
        let mut t = all.clone();
        t.t_end = Some(1.0);
        assert!(!all.covers(&t) && !t.covers(&all));
    }

    /// `admits` selects a key exactly when every filter names it (or is empty).
    #[test]
    fn admits_matches_every_filter() {
        use crate::summary::RunKey;
        let s = sel(&["nine_spring"], &["so3", "quat_proj"]);
        assert!(s.admits(&RunKey::new("nine_spring", "x", "so3", "rk4", "body")));
        assert!(s.admits(&RunKey::new(
            "nine_spring",
            "y",
            "quat_proj",
            "rk4",
            "spatial"
        )));
        assert!(!s.admits(&RunKey::new("nine_spring", "x", "rotvec", "rk4", "body")));
        assert!(!s.admits(&RunKey::new("free_body", "x", "so3", "rk4", "body")));
    }

    /// The flags and the slug name every filter in the command line's order.
    #[test]
    fn flags_and_slug() {
        let mut s = sel(&["nine_spring"], &["so3"]);
        s.t_end = Some(2.5);
        assert_eq!(s.flags(), "--case nine_spring --param so3 --t-end 2.5");
        assert_eq!(s.slug(), "nine_spring-so3-t2.5");
        assert_eq!(Selection::everything(Tier::Full).flags(), "");
        assert!(Selection::everything(Tier::Full).is_everything());
    }

    /// A selection read from a file is refused, naming its key, when a filter repeats a name,
    /// lists more than MAX_NAMES names, holds something that is not a name, or when `t_end`
    /// is not a positive time (a fuzzed summary with 130,000 copies of a case name made the
    /// report allocate 219 MB); a command line's selection passes.
    #[test]
    fn check_refuses_hostile_selections() {
        let ok = sel(&["nine_spring", "free_body"], &["so3"]);
        assert!(ok.check().is_ok());
        let repeated = sel(
            &["nine_spring", "free_body", "nine_spring"],
            &["so3", "so3"],
        );
        assert_eq!(repeated.deduped(), ok);
        assert!(Selection::everything(Tier::Quick).check().is_ok());
        let mut twice = ok.clone();
        twice.cases.push("nine_spring".into());
        assert!(twice.check().unwrap_err().contains("selection.cases[2]"));
        let mut many = Selection::everything(Tier::Quick);
        many.integrators = (0..=MAX_NAMES).map(|i| format!("m{i}")).collect();
        assert!(many.check().unwrap_err().contains("selection.integrators"));
        let mut odd = ok.clone();
        odd.params = vec!["so3\n--out /".into()];
        assert!(odd.check().unwrap_err().contains("selection.params[0]"));
        let mut long = ok.clone();
        long.scenes = vec!["x".repeat(MAX_NAME_LEN + 1)];
        assert!(long.check().unwrap_err().contains("selection.scenes[0]"));
        let mut t = ok;
        t.t_end = Some(-1.0);
        assert!(t.check().unwrap_err().contains("selection.t_end"));
    }
}
