//! Step ladders (cases/README.md, "`[ladders]`": a scene's override, the `quick` tier):
//! fixed steps per method order class and tolerances for adaptive methods, each fixed step
//! resolved against its scene by the divides rule of the case-file conventions
//! (`n = round(T/h)`, `|n h - T| <= 1e-9 T`, `1 <= n <= 9e15`; the run then takes `n` steps of
//! `T/n`) and the case's `max_steps`. Shared by every model family.
//!
//! Invariants after loading: every value is finite and positive, tolerances lie in (0, 1), no
//! list holds a value twice, every step divides `score_every` and needs at most `max_steps`
//! steps over the scene.
use serde::Deserialize;

use super::{Ctx, Res};

/// Relative slack of the step-divides-span rule.
pub const DIVIDES_REL_TOL: f64 = 1e-9;

/// Fixed-step integrator classes, each with its own ladder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum OrderClass {
    /// Order 1 (`order1`).
    Order1,
    /// Orders 2 to 4 (`order2_4`).
    Order2To4,
    /// Order 5 and above (`order6`).
    Order6,
}

impl OrderClass {
    pub const ALL: [OrderClass; 3] = [
        OrderClass::Order1,
        OrderClass::Order2To4,
        OrderClass::Order6,
    ];

    /// The class of a method of order `order` (None for 0).
    pub fn of_order(order: u32) -> Option<Self> {
        match order {
            0 => None,
            1 => Some(OrderClass::Order1),
            2..=4 => Some(OrderClass::Order2To4),
            _ => Some(OrderClass::Order6),
        }
    }

    /// Its key in `[ladders]`.
    pub fn key(self) -> &'static str {
        match self {
            OrderClass::Order1 => "order1",
            OrderClass::Order2To4 => "order2_4",
            OrderClass::Order6 => "order6",
        }
    }
}

/// One point of a fixed-step ladder, resolved against its scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LadderStep {
    /// The step as written in the file (s); records and gates name the run by it.
    pub dt: f64,
    /// Steps per `score_every`: `round(score_every / dt)`.
    pub per_score: u64,
    /// Steps over the whole scene: `per_score * Scene::n_score`.
    pub steps: u64,
    /// The step actually taken: `t_end / steps` (`t_k = k h`, the run ends at `t_end`).
    pub h: f64,
}

/// A scene's effective ladders (the scene's override where given, else the case's).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Ladder {
    pub order1: Vec<LadderStep>,
    pub order2_4: Vec<LadderStep>,
    pub order6: Vec<LadderStep>,
    /// Adaptive tolerances, each in (0, 1).
    pub tol: Vec<f64>,
    /// The key path each class's list came from (`ladders.order1`,
    /// `scene[2].ladders.quick.order6`; empty for a class without a list), in
    /// `OrderClass::ALL` order.
    pub paths: [String; 3],
}

impl Ladder {
    /// The fixed steps of one class.
    pub fn fixed(&self, class: OrderClass) -> &[LadderStep] {
        match class {
            OrderClass::Order1 => &self.order1,
            OrderClass::Order2To4 => &self.order2_4,
            OrderClass::Order6 => &self.order6,
        }
    }

    /// The step of one class that takes the most steps, with its key path
    /// (`ladders.order2_4[3]`); None for an empty class.
    pub fn finest(&self, class: OrderClass) -> Option<(String, LadderStep)> {
        let i = OrderClass::ALL.iter().position(|c| *c == class)?;
        self.fixed(class)
            .iter()
            .enumerate()
            .max_by_key(|(_, s)| s.steps)
            .map(|(j, s)| (format!("{}[{j}]", self.paths[i]), *s))
    }
}

/// Step ladders per method order class, and tolerances for adaptive methods.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Ladders {
    pub order1: Vec<f64>,
    pub order2_4: Vec<f64>,
    pub order6: Vec<f64>,
    pub tol: Vec<f64>,
}

impl Ladders {
    /// The ladder a method runs on.
    pub fn for_method(&self, info: &crate::integrate::MethodInfo) -> &[f64] {
        if info.adaptive {
            &self.tol
        } else if info.order <= 1 {
            &self.order1
        } else if info.order <= 4 {
            &self.order2_4
        } else {
            &self.order6
        }
    }
}

impl Ladder {
    /// The ladder's values: the nominal steps of each order class and the tolerances.
    pub fn values(&self) -> Ladders {
        let dts = |c: OrderClass| self.fixed(c).iter().map(|s| s.dt).collect::<Vec<_>>();
        Ladders {
            order1: dts(OrderClass::Order1),
            order2_4: dts(OrderClass::Order2To4),
            order6: dts(OrderClass::Order6),
            tol: self.tol.clone(),
        }
    }
}

/// The number of steps `n = round(span / h)` when `h` divides `span` by the rule of
/// cases/README.md, "Conventions" (`|n h - span| <= 1e-9 span`, `n >= 1`); None otherwise, and for
/// a non-finite or non-positive argument.
pub fn steps_dividing(span: f64, h: f64) -> Option<u64> {
    if !(span.is_finite() && h.is_finite() && span > 0.0 && h > 0.0) {
        return None;
    }
    let n = (span / h).round();
    if !(1.0..=9.0e15).contains(&n) {
        return None;
    }
    if (n * h - span).abs() <= DIVIDES_REL_TOL * span {
        Some(n as u64)
    } else {
        None
    }
}

// ---------------------------------------------------------------------------------------

/// The part of a scene the ladders are resolved against.
pub(crate) struct Span {
    pub index: usize,
    pub name: String,
    pub t_end: f64,
    pub score_every: f64,
    pub n_score: u64,
}

/// `[ladders]` as written (the case's, or a scene's override).
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawLadders {
    order1: Option<Vec<f64>>,
    order2_4: Option<Vec<f64>>,
    order6: Option<Vec<f64>>,
    tol: Option<Vec<f64>>,
    quick: Option<RawQuick>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawQuick {
    order1: Option<Vec<f64>>,
    order2_4: Option<Vec<f64>>,
    order6: Option<Vec<f64>>,
    tol: Option<Vec<f64>>,
}

impl RawLadders {
    fn get(&self, key: &str) -> Option<&Vec<f64>> {
        match key {
            "order1" => self.order1.as_ref(),
            "order2_4" => self.order2_4.as_ref(),
            "order6" => self.order6.as_ref(),
            _ => self.tol.as_ref(),
        }
    }
}

fn quick_list<'a>(l: &'a RawLadders, key: &str) -> Option<&'a Vec<f64>> {
    l.quick.as_ref().and_then(|q| q.get(key))
}

impl RawQuick {
    fn get(&self, key: &str) -> Option<&Vec<f64>> {
        match key {
            "order1" => self.order1.as_ref(),
            "order2_4" => self.order2_4.as_ref(),
            "order6" => self.order6.as_ref(),
            _ => self.tol.as_ref(),
        }
    }
}

impl Ctx<'_> {
    /// Values of a ladder table that do not depend on a scene: finite, positive, tols in
    /// (0, 1), no duplicates; the case-level table must give all four lists.
    pub(crate) fn ladders_shape(&self, prefix: &str, l: &RawLadders, complete: bool) -> Res<()> {
        for key in ["order1", "order2_4", "order6", "tol"] {
            match l.get(key) {
                Some(v) => self.list_shape(&format!("{prefix}.{key}"), key, v)?,
                None if complete => {
                    return self.err(
                        format!("{prefix}.{key}"),
                        "missing; expected a list (it may be empty)",
                    );
                }
                None => {}
            }
            if let Some(v) = l.quick.as_ref().and_then(|q| q.get(key)) {
                self.list_shape(&format!("{prefix}.quick.{key}"), key, v)?;
            }
        }
        Ok(())
    }

    fn list_shape(&self, path: &str, key: &str, v: &[f64]) -> Res<()> {
        // Values are checked finite and positive before they are compared, so equal values
        // have equal bits: a set finds the repeat in O(n) (a scan of the earlier values was
        // quadratic: 125 s for a ladder of 1e6 tolerances).
        let mut seen = std::collections::HashSet::with_capacity(v.len());
        for (j, x) in v.iter().enumerate() {
            let k = format!("{path}[{j}]");
            if key == "tol" {
                let x = self.finite(&k, *x)?;
                if !(x > 0.0 && x < 1.0) {
                    return self.err(k, format!("{x}; expected a tolerance in (0, 1)"));
                }
            } else {
                self.positive(&k, *x, "a step in s")?;
            }
            if !seen.insert(x.to_bits()) {
                return self.err(k, format!("{x} appears twice; expected distinct values"));
            }
        }
        Ok(())
    }

    /// One tier of a scene's effective ladder.
    pub(crate) fn tier(
        &self,
        case_l: &RawLadders,
        scene_l: Option<&RawLadders>,
        quick: bool,
        span: &Span,
        max_steps: u64,
    ) -> Res<Ladder> {
        let pick = |key: &str| -> Option<(String, &Vec<f64>)> {
            if quick {
                if let Some(v) = scene_l.and_then(|l| quick_list(l, key)) {
                    return Some((format!("scene[{}].ladders.quick.{key}", span.index), v));
                }
                quick_list(case_l, key).map(|v| (format!("ladders.quick.{key}"), v))
            } else {
                if let Some(v) = scene_l.and_then(|l| l.get(key)) {
                    return Some((format!("scene[{}].ladders.{key}", span.index), v));
                }
                case_l.get(key).map(|v| (format!("ladders.{key}"), v))
            }
        };
        let mut out = Ladder::default();
        for (i, class) in OrderClass::ALL.into_iter().enumerate() {
            let steps = match pick(class.key()) {
                Some((path, v)) => {
                    let steps = v
                        .iter()
                        .enumerate()
                        .map(|(j, h)| self.fixed_step(&format!("{path}[{j}]"), *h, span, max_steps))
                        .collect::<Res<Vec<_>>>()?;
                    out.paths[i] = path;
                    steps
                }
                None => Vec::new(),
            };
            match class {
                OrderClass::Order1 => out.order1 = steps,
                OrderClass::Order2To4 => out.order2_4 = steps,
                OrderClass::Order6 => out.order6 = steps,
            }
        }
        out.tol = pick("tol").map(|(_, v)| v.clone()).unwrap_or_default();
        Ok(out)
    }

    fn fixed_step(&self, key: &str, dt: f64, span: &Span, max_steps: u64) -> Res<LadderStep> {
        let Some(per_score) = steps_dividing(span.score_every, dt) else {
            return self.err(
                key,
                format!(
                    "step {dt} s does not divide score_every = {} s of scene `{}`; expected \
                     score_every / step to be an integer (to 1e-9 relative)",
                    span.score_every, span.name
                ),
            );
        };
        let steps = per_score.saturating_mul(span.n_score);
        if steps > max_steps {
            return self.err(
                key,
                format!(
                    "step {dt} s needs {steps} steps over t_end = {} s of scene `{}`, more \
                     than max_steps = {max_steps}",
                    span.t_end, span.name
                ),
            );
        }
        Ok(LadderStep {
            dt,
            per_score,
            steps,
            h: span.t_end / steps as f64,
        })
    }
}
