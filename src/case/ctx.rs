//! The validation context of a case file ([`Ctx`]): the checks every family's loader uses
//! (finite, positive, lengths between [`MIN_LENGTH`](super::MIN_LENGTH) and
//! [`MAX_LENGTH`](super::MAX_LENGTH), counts, names, budget keys up to their hard caps) and
//! [`Ctx::assemble`], which validates the shared keys (identity, primary metric, budgets,
//! advice targets, each scene's grid and ladders, gates, `[stability]`) around a family's own
//! physics. Every check returns an error naming the file, the key and what was expected;
//! none panics.
use nalgebra::Vector3;

use super::*;

/// The validation context: which file errors name.
pub struct Ctx<'a> {
    pub file: &'a str,
}

/// A loading result.
pub type Res<T> = Result<T, CaseError>;

impl Ctx<'_> {
    pub fn err<T>(&self, key: impl Into<String>, message: impl Into<String>) -> Res<T> {
        Err(CaseError {
            file: self.file.to_string(),
            key: key.into(),
            message: message.into(),
        })
    }

    pub fn finite(&self, key: &str, x: f64) -> Res<f64> {
        if x.is_finite() {
            Ok(x)
        } else {
            self.err(key, format!("{x} is not a finite number"))
        }
    }

    pub fn positive(&self, key: &str, x: f64, what: &str) -> Res<f64> {
        let x = self.finite(key, x)?;
        if x > 0.0 {
            Ok(x)
        } else {
            self.err(key, format!("{x} is not positive; expected {what} > 0"))
        }
    }

    /// A length that sets a model's size: finite, from [`MIN_LENGTH`] to [`MAX_LENGTH`] m.
    pub fn length(&self, key: &str, x: f64, what: &str) -> Res<f64> {
        let x = self.positive(key, x, what)?;
        if !(MIN_LENGTH..=MAX_LENGTH).contains(&x) {
            return self.err(
                key,
                format!(
                    "{x:e} m; expected {what} from {MIN_LENGTH} to {MAX_LENGTH} m \
                     (cases/README.md, \"Conventions\": lengths)"
                ),
            );
        }
        Ok(x)
    }

    pub fn vec3(&self, key: &str, a: [f64; 3]) -> Res<Vector3<f64>> {
        for (i, x) in a.iter().enumerate() {
            self.finite(&format!("{key}[{i}]"), *x)?;
        }
        Ok(Vector3::from(a))
    }

    pub fn count(&self, key: &str, x: f64) -> Res<u64> {
        let x = self.finite(key, x)?;
        if x >= 1.0 && x.fract() == 0.0 && x <= 9.0e15 {
            Ok(x as u64)
        } else {
            self.err(key, format!("{x}; expected a positive integer"))
        }
    }

    /// A budget key: a count up to its hard cap (`budget::HARD_CAPS`), or `default` when
    /// absent.
    fn budget_key(&self, key: &str, raw: Option<f64>, default: u64) -> Res<u64> {
        let Some(x) = raw else {
            return Ok(default);
        };
        let n = self.count(key, x)?;
        let cap = hard_cap(key);
        if n > cap {
            return self.err(
                key,
                format!("{n} is above its hard cap {cap} (cases/README.md, \"Budgets\")"),
            );
        }
        Ok(n)
    }

    pub fn name(&self, key: &str, s: &str, allow: impl Fn(char) -> bool, what: &str) -> Res<()> {
        if !s.is_empty() && s.chars().all(allow) {
            Ok(())
        } else {
            self.err(key, format!("`{s}`; expected {what}"))
        }
    }

    /// The file's `schema`, its `case` name (snake_case) and its `title`: one line without
    /// control characters, since the title reaches the terminal (`list`) and summary.md, where
    /// a newline could forge a heading and an ESC a terminal control sequence.
    fn identity(&self, raw: &RawShared) -> Res<()> {
        if raw.schema != SCHEMA {
            return self.err("schema", format!("{}; expected {SCHEMA}", raw.schema));
        }
        self.name(
            "case",
            &raw.case,
            |c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_',
            "a snake_case name ([a-z0-9_]+)",
        )?;
        if raw.title.chars().any(char::is_control) {
            return self.err(
                "title",
                format!(
                    "{:?} holds a control character (a newline, tab, ESC, ...); expected one \
                     line of plain text",
                    raw.title
                ),
            );
        }
        Ok(())
    }

    /// `advise_targets`: absent, or a non-empty list of distinct positive errors.
    fn advise_targets(&self, targets: Option<&[f64]>) -> Res<Option<Vec<f64>>> {
        let Some(t) = targets else {
            return Ok(None);
        };
        if t.is_empty() {
            return self.err(
                "advise_targets",
                "empty; expected at least one target error",
            );
        }
        let mut seen = std::collections::HashSet::new();
        for (i, &x) in t.iter().enumerate() {
            let k = format!("advise_targets[{i}]");
            self.positive(&k, x, "an error in the primary metric's unit")?;
            if !seen.insert(x.to_bits()) {
                return self.err(k, format!("{x} is listed twice"));
            }
        }
        Ok(Some(t.to_vec()))
    }

    /// The family's `reference` kind named `name`; any other name is refused, with the
    /// family's kinds.
    fn reference_kind(&self, family: &dyn super::CaseFamily, name: &str) -> Res<ReferenceKind> {
        if let Some(k) = family.references().iter().find(|k| k.name() == name) {
            return Ok(*k);
        }
        let kinds: Vec<String> = family
            .references()
            .iter()
            .map(|k| format!("`{}`", k.name()))
            .collect();
        self.err(
            "reference",
            format!(
                "`{name}`; a {} case's references are {}",
                family.model(),
                kinds.join(" or ")
            ),
        )
    }

    /// The shared part of a case: checks the shared keys, lets the family check its own
    /// (`case_physics` once, before the scenes; `scene_physics` per scene, after its name),
    /// resolves every scene's grid and ladders, then the gates and `[stability]`.
    pub fn assemble<C: Payload, O, S: Payload>(
        &self,
        family: &'static dyn super::CaseFamily,
        raw: RawShared,
        case_physics: impl FnOnce(&Self) -> Res<C>,
        scenes: Vec<(RawGrid, O)>,
        scene_physics: impl Fn(&Self, usize, &O, &C) -> Res<S>,
    ) -> Res<Case> {
        self.identity(&raw)?;
        let metrics = family.metric_names();
        if !metrics.contains(&raw.primary_metric.as_str()) {
            return self.err(
                "primary_metric",
                format!(
                    "unknown metric `{}`; expected one of {}",
                    raw.primary_metric,
                    metrics.join(", ")
                ),
            );
        }
        let reference = self.reference_kind(family, &raw.reference)?;
        let energy_scale = self.positive("energy_scale", raw.energy_scale, "an energy in J")?;
        let max_steps = self.budget_key("max_steps", raw.max_steps, DEFAULT_MAX_STEPS)?;
        let max_rhs_evals =
            self.budget_key("max_rhs_evals", raw.max_rhs_evals, DEFAULT_MAX_RHS_EVALS)?;
        let max_adaptive_rhs_evals = self.budget_key(
            "max_adaptive_rhs_evals",
            raw.max_adaptive_rhs_evals,
            DEFAULT_MAX_ADAPTIVE_RHS_EVALS,
        )?;
        let max_memory_mib =
            self.budget_key("max_memory_mib", raw.max_memory_mib, DEFAULT_MAX_MEMORY_MIB)?;
        let max_work = self.budget_key("max_work", raw.max_work, DEFAULT_MAX_WORK)?;
        let advise_targets = self.advise_targets(raw.advise_targets.as_deref())?;
        let advise_max_energy_drift = match raw.advise_max_energy_drift {
            Some(x) => self.positive("advise_max_energy_drift", x, "a relative drift")?,
            None => DEFAULT_ADVISE_MAX_ENERGY_DRIFT,
        };
        let physics = case_physics(self)?;
        self.ladders_shape("ladders", &raw.ladders, true)?;
        if scenes.is_empty() {
            return self.err("scene", "no [[scene]]; expected at least one");
        }
        let mut out: Vec<Scene> = Vec::with_capacity(scenes.len());
        for (i, (grid, own)) in scenes.iter().enumerate() {
            self.name(
                &format!("scene[{i}].name"),
                &grid.name,
                |c| c.is_ascii_alphanumeric() || c == '_' || c == '-',
                "a scene name matching [A-Za-z0-9_-]+",
            )?;
            let scene_physics = scene_physics(self, i, own, &physics)?;
            let scene = self.grid(
                i,
                grid,
                &raw.ladders,
                max_steps,
                Physics::new(scene_physics),
            )?;
            if out.iter().any(|o| o.name == scene.name) {
                return self.err(
                    format!("scene[{i}].name"),
                    format!(
                        "`{}` is used twice; expected unique scene names",
                        scene.name
                    ),
                );
            }
            out.push(scene);
        }
        let gates = raw
            .gates
            .into_iter()
            .enumerate()
            .map(|(i, g)| self.gate(i, g, &out, family.formulations()))
            .collect::<Res<Vec<_>>>()?;
        let stability = raw
            .stability
            .map(|st| self.stability(st, &out))
            .transpose()?;
        Ok(Case {
            file: self.file.to_string(),
            name: raw.case,
            title: raw.title,
            family,
            primary_metric: raw.primary_metric,
            energy_scale,
            reference,
            max_steps,
            max_rhs_evals,
            max_adaptive_rhs_evals,
            max_memory_mib,
            max_work,
            advise_targets,
            advise_max_energy_drift,
            scenes: out,
            gates,
            stability,
            physics: Physics::new(physics),
        })
    }

    fn stability(&self, st: RawStability, scenes: &[Scene]) -> Res<StabilitySpec> {
        let periods = st
            .periods
            .map(|x| self.positive("stability.periods", x, "a number of periods"))
            .transpose()?;
        let rotation_error_max = st
            .rotation_error_max
            .map(|x| {
                self.positive(
                    "stability.rotation_error_max",
                    x,
                    "a rotation error bound in rad",
                )
            })
            .transpose()?;
        for (i, name) in st.quick.iter().enumerate() {
            if !scenes.iter().any(|s| &s.name == name) {
                return self.err(
                    format!("stability.quick[{i}]"),
                    format!("`{name}` is no scene of this case"),
                );
            }
        }
        Ok(StabilitySpec {
            periods,
            rotation_error_max,
            quick: st.quick,
        })
    }

    /// A scene's horizon, grids and ladders.
    fn grid(
        &self,
        i: usize,
        s: &RawGrid,
        case_l: &RawLadders,
        max_steps: u64,
        physics: Physics,
    ) -> Res<Scene> {
        let key = |k: &str| format!("scene[{i}].{k}");
        let t_end = self.positive(&key("t_end"), s.t_end, "a horizon in s")?;
        let sample_every = self.positive(&key("sample_every"), s.sample_every, "a time in s")?;
        let score_every = self.positive(&key("score_every"), s.score_every, "a time in s")?;
        let Some(n_score) = steps_dividing(t_end, score_every) else {
            return self.err(
                key("score_every"),
                format!(
                    "{score_every} s does not divide t_end = {t_end} s; expected t_end / \
                     score_every to be an integer (to 1e-9 relative)"
                ),
            );
        };
        let Some(samples_per_score) = steps_dividing(score_every, sample_every) else {
            return self.err(
                key("sample_every"),
                format!(
                    "{sample_every} s does not divide score_every = {score_every} s; expected \
                     score_every / sample_every to be an integer (to 1e-9 relative)"
                ),
            );
        };
        if let Some(why) = over_sample_budget(n_score, samples_per_score) {
            return self.err(key("sample_every"), why);
        }
        if let Some(l) = &s.ladders {
            self.ladders_shape(&key("ladders"), l, false)?;
        }
        let span = ladder::Span {
            index: i,
            name: s.name.clone(),
            t_end,
            score_every,
            n_score,
        };
        let ladders = self.tier(case_l, s.ladders.as_ref(), false, &span, max_steps)?;
        let quick = self.tier(case_l, s.ladders.as_ref(), true, &span, max_steps)?;
        Ok(Scene {
            name: s.name.clone(),
            index: i,
            t_end,
            sample_every,
            score_every,
            n_score,
            samples_per_score,
            ladders,
            quick,
            control: s.control,
            physics,
            settings_sha256: String::new(),
        })
    }
}
