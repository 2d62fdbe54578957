//! The report's view of a summary: records grouped by case, scene and variant, each variant's
//! ladder sorted coarse to fine (largest step or loosest tolerance first), with its order fit,
//! plus the per-run series files found on disk.
//!
//! Invariants: variants appear in the families' axis order (`catalogue::axis_names`;
//! names no family has sort after, alphabetically); scenes in the case file's order
//! (unknown scenes after, alphabetically); cases in the order of the `cases` slice, then cases
//! absent from it. A variant's runs are either all fixed-step (`dt`) or all adaptive (`tol`).
//! A variant's method facts (kind, twin) are the summary's (`catalogue::methods_of`).
//! A missing or unreadable series file is `None`, never an error: the plots say "no data".
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::case::Case;
use crate::catalogue::axis_position;
use crate::integrate::MethodKind;
use crate::problem::{Axis, Family};
use crate::summary::methods::Methods;
use crate::summary::{FitRecord, Record, RunKey, Series, Status, Summary, run_id};

/// A variant: parameterization x integrator x formulation.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct VariantKey {
    pub param: String,
    pub integrator: String,
    pub formulation: String,
}

impl VariantKey {
    /// The variant of a record's or a fit's run key.
    pub fn of(k: &RunKey) -> Self {
        VariantKey {
            param: k.param.clone(),
            integrator: k.integrator.clone(),
            formulation: k.formulation.clone(),
        }
    }

    /// `param / integrator / formulation`.
    pub fn label(&self) -> String {
        format!(
            "{} / {} / {}",
            self.param, self.integrator, self.formulation
        )
    }

    /// Whether the parameterization belongs to its family's contrasted chart group (the rigid
    /// body's Euler-angle charts; `problem::figures::ChartGroup`).
    pub fn in_chart_group(&self) -> bool {
        crate::catalogue::family_of_variant(&self.param, &self.integrator, &self.formulation)
            .figures
            .chart_group
            .is_some_and(|g| g.contains(&self.param))
    }

    fn rank(&self) -> (usize, &str, usize, &str, usize, &str) {
        (
            axis_position(Axis::Param, &self.param),
            &self.param,
            axis_position(Axis::Integrator, &self.integrator),
            &self.integrator,
            axis_position(Axis::Formulation, &self.formulation),
            &self.formulation,
        )
    }
}

impl PartialOrd for VariantKey {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for VariantKey {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.rank().cmp(&other.rank())
    }
}

/// What a scene's `t` is, as its family declares (`Figures::t_axis`): the label of `t` and of
/// its step; `("t", "step dt")` when the case file was not given.
pub fn t_labels(cv: &CaseView, scene: &str) -> (&'static str, &'static str) {
    cv.case
        .and_then(|c| c.scene(scene))
        .map_or(("t", "step dt"), |s| (cv.family.figures.t_axis)(s))
}

/// A metric's axis label with its unit as the family declares it (`rotation_error_max (rad)`;
/// `(1)` for a relative one); the bare name when the family does not declare it.
pub fn with_unit(cv: &CaseView, metric: &str) -> String {
    match cv.family.metrics.iter().find(|m| m.name == metric) {
        Some(m) if !m.unit.is_empty() => format!("{metric} ({})", m.unit),
        _ => metric.to_string(),
    }
}

/// The label of a scene's error axis: the primary metric with its unit, and, where the
/// reference is itself one of the variants, whose distance it is.
pub fn error_label(cv: &CaseView, sv: &SceneView) -> String {
    let base = with_unit(cv, &cv.primary);
    match &sv.reference {
        Some(r) => format!("{base}, distance to {r}"),
        None => base,
    }
}

/// A caption's sentence saying that a scene's errors are distances to a variant (empty where
/// the reference is converged or exact).
pub fn reference_clause(sv: &SceneView) -> String {
    match &sv.reference {
        Some(r) => format!(
            " The reference is {r}, itself one of the variants: every error here is a distance \
             to that scheme, not to the exact solution."
        ),
        None => String::new(),
    }
}

/// How a metric gathers its run, from its name's suffix (the metric names' convention):
/// ` (max over the run)` for `_max`, ` (RMS over the run)` for `_rms`, ` (at the end)` for
/// `_final`, nothing otherwise.
pub fn aggregate(metric: &str) -> &'static str {
    if metric.ends_with("_max") {
        " (max over the run)"
    } else if metric.ends_with("_rms") {
        " (RMS over the run)"
    } else if metric.ends_with("_final") {
        " (at the end)"
    } else {
        ""
    }
}

/// A record's ladder value: its step (s) or its tolerance.
pub fn step_of(r: &Record) -> Option<f64> {
    r.dt.or(r.tol)
}

/// `dt 1e-2` or `tol 1e-8`.
pub fn step_label(r: &Record) -> String {
    match (r.dt, r.tol) {
        (Some(h), _) => format!("dt {}", num(h)),
        (None, Some(t)) => format!("tol {}", num(t)),
        _ => "-".into(),
    }
}

/// A number with 3 significant digits (`1.23e-4`), or a plain integer below 1e6.
pub fn num(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == x.trunc() && x.abs() < 1e6 {
        return format!("{x:.0}");
    }
    let s = format!("{x:.2e}");
    // 1.00e-2 -> 1e-2, 1.50e-2 -> 1.5e-2.
    match s.split_once('e') {
        Some((m, e)) => {
            let m = m.trim_end_matches('0').trim_end_matches('.');
            format!("{m}e{e}")
        }
        None => s,
    }
}

/// A time in seconds: plain decimals with up to 4 significant digits between 1e-3 and 1e5
/// (`0.5`, `1.571`, `20`), else as `num`.
pub fn time(t: f64) -> String {
    if t == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e5).contains(&t.abs()) {
        return num(t);
    }
    let decimals = (3 - t.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{t:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// All runs of one variant in one scene.
#[derive(Debug, Clone)]
pub struct VariantRuns<'a> {
    pub key: VariantKey,
    /// Coarse to fine: decreasing `dt` (or `tol`).
    pub runs: Vec<&'a Record>,
    /// Adaptive (`tol`) rather than fixed-step (`dt`).
    pub adaptive: bool,
    /// The method's kind, by the summary's facts (`catalogue::methods_of`).
    pub kind: MethodKind,
    /// Whether the method is, by the summary's facts, a long-horizon twin of another.
    pub twin: bool,
    /// The order fit on the primary metric, if the summary has one.
    pub fit: Option<&'a FitRecord>,
}

impl<'a> VariantRuns<'a> {
    /// The runs that completed.
    pub fn ok(&self) -> impl Iterator<Item = &'a Record> + '_ {
        self.runs.iter().copied().filter(|r| r.status == Status::Ok)
    }
    /// The runs that ended with a typed failure.
    pub fn failed(&self) -> impl Iterator<Item = &'a Record> + '_ {
        self.runs
            .iter()
            .copied()
            .filter(|r| r.status == Status::Failed)
    }
    /// The coarsest completed run (largest step, loosest tolerance).
    pub fn coarsest_ok(&self) -> Option<&'a Record> {
        self.ok().next()
    }
    /// The finest run of the ladder (the terminal table's row).
    pub fn finest(&self) -> Option<&'a Record> {
        self.runs.last().copied()
    }
    /// The run at ladder value `v` (relative match 1e-9).
    pub fn at(&self, v: f64) -> Option<&'a Record> {
        self.runs
            .iter()
            .copied()
            .find(|r| step_of(r).is_some_and(|s| (s - v).abs() <= 1e-9 * v.abs()))
    }
}

/// One scene of a case.
#[derive(Debug, Clone)]
pub struct SceneView<'a> {
    pub name: String,
    /// Registered variants that ran (ok or failed), in registry order.
    pub variants: Vec<VariantRuns<'a>>,
    /// `n/a` records (with their reasons).
    pub na: Vec<&'a Record>,
    /// The reference's label when it is itself one of the variants
    /// (`problem::ReferenceVariant::label`): the scene's errors are distances to it.
    pub reference: Option<String>,
}

impl<'a> SceneView<'a> {
    /// The runs of a variant.
    pub fn variant(
        &self,
        param: &str,
        integrator: &str,
        formulation: &str,
    ) -> Option<&VariantRuns<'a>> {
        self.variants.iter().find(|v| {
            v.key.param == param
                && v.key.integrator == integrator
                && v.key.formulation == formulation
        })
    }
    /// Every run record of the scene (not `n/a`).
    pub fn runs(&self) -> impl Iterator<Item = &'a Record> + '_ {
        self.variants.iter().flat_map(|v| v.runs.iter().copied())
    }
}

/// One case with its scenes.
#[derive(Debug, Clone)]
pub struct CaseView<'a> {
    pub name: String,
    pub title: String,
    /// The case's primary error metric.
    pub primary: String,
    /// J: relative energy drifts divide by `max(|E0|, energy_scale)` (None: the case file was
    /// not given, drifts divide by `|E0|`).
    pub energy_scale: Option<f64>,
    pub scenes: Vec<SceneView<'a>>,
    /// The case file, when it was given.
    pub case: Option<&'a Case>,
    /// The case's model family: its figures, names and metrics.
    pub family: &'static Family,
}

impl<'a> CaseView<'a> {
    /// Every run record of the case.
    pub fn runs(&self) -> impl Iterator<Item = &'a Record> + '_ {
        self.scenes.iter().flat_map(|s| s.runs())
    }
    /// The metrics any record of the case has, in the family's metric order (primary first),
    /// then unknown names alphabetically.
    pub fn metrics(&self) -> Vec<String> {
        let mut set: std::collections::BTreeSet<&str> = Default::default();
        for s in &self.scenes {
            for r in s.runs() {
                set.extend(r.metrics.keys().map(|k| k.as_str()));
            }
        }
        let family = self
            .case
            .map(crate::catalogue::family_of)
            .unwrap_or(crate::catalogue::FAMILIES[0]);
        let known: Vec<&str> = family.metrics.iter().map(|m| m.name).collect();
        let mut out: Vec<String> = vec![];
        if set.contains(self.primary.as_str()) {
            out.push(self.primary.clone());
        }
        for m in &known {
            if set.contains(m) && *m != self.primary {
                out.push(m.to_string());
            }
        }
        for m in set {
            if !known.contains(&m) && m != self.primary {
                out.push(m.to_string());
            }
        }
        out
    }
}

/// Groups a summary's records into cases, scenes and variants.
pub fn case_views<'a>(summary: &'a Summary, cases: &'a [Case]) -> Vec<CaseView<'a>> {
    let mut by_case: BTreeMap<&str, BTreeMap<&str, Vec<&'a Record>>> = BTreeMap::new();
    for r in &summary.records {
        by_case
            .entry(&r.key.case)
            .or_default()
            .entry(&r.key.scene)
            .or_default()
            .push(r);
    }
    let methods = crate::catalogue::methods_of(summary);
    let mut fits: BTreeMap<(&str, &str, VariantKey), &'a FitRecord> = BTreeMap::new();
    for f in &summary.fits {
        fits.insert((&f.key.case, &f.key.scene, VariantKey::of(&f.key)), f);
    }
    let mut names: Vec<&str> = cases
        .iter()
        .map(|c| c.name.as_str())
        .filter(|n| by_case.contains_key(n))
        .collect();
    for n in by_case.keys() {
        if !names.contains(n) {
            names.push(n);
        }
    }
    names
        .into_iter()
        .map(|name| {
            let case = cases.iter().find(|c| c.name == name);
            let scenes_map = &by_case[name];
            let mut scene_names: Vec<&str> = case
                .map(|c| {
                    c.scenes
                        .iter()
                        .map(|s| s.name.as_str())
                        .filter(|s| scenes_map.contains_key(s))
                        .collect()
                })
                .unwrap_or_default();
            for s in scenes_map.keys() {
                if !scene_names.contains(s) {
                    scene_names.push(s);
                }
            }
            let scenes = scene_names
                .into_iter()
                .map(|scene| scene_view(name, scene, &scenes_map[scene], &fits, &methods))
                .collect();
            let family =
                crate::catalogue::family_of_case(case, scenes_map.values().flatten().copied());
            let primary = case
                .map(|c| c.primary_metric.clone())
                .or_else(|| {
                    summary
                        .fits
                        .iter()
                        .find(|f| f.key.case == name)
                        .map(|f| f.metric.clone())
                })
                .unwrap_or_else(|| family.default_primary().to_string());
            CaseView {
                name: name.to_string(),
                title: case.map(|c| c.title.clone()).unwrap_or_default(),
                primary,
                energy_scale: case.map(|c| c.energy_scale),
                scenes,
                case,
                family,
            }
        })
        .collect()
}

fn scene_view<'a>(
    case: &str,
    scene: &str,
    records: &[&'a Record],
    fits: &BTreeMap<(&str, &str, VariantKey), &'a FitRecord>,
    methods: &Methods,
) -> SceneView<'a> {
    let mut na = vec![];
    let mut groups: BTreeMap<VariantKey, Vec<&'a Record>> = BTreeMap::new();
    for r in records {
        if r.status == Status::NotApplicable {
            na.push(*r);
        } else {
            groups.entry(VariantKey::of(&r.key)).or_default().push(*r);
        }
    }
    let variants = groups
        .into_iter()
        .map(|(key, mut runs)| {
            runs.sort_by(|a, b| {
                step_of(b)
                    .unwrap_or(0.0)
                    .total_cmp(&step_of(a).unwrap_or(0.0))
            });
            let adaptive = runs.iter().all(|r| r.dt.is_none() && r.tol.is_some());
            let fit = fits.get(&(case, scene, key.clone())).copied();
            let kind = super::select::kind_of(methods, &key.integrator);
            let twin = super::select::is_twin(methods, &key.integrator);
            VariantRuns {
                key,
                runs,
                adaptive,
                kind,
                twin,
                fit,
            }
        })
        .collect();
    SceneView {
        name: scene.to_string(),
        variants,
        na,
        reference: None,
    }
}

/// Whether `rel` stays inside the folder it is joined to: relative, and made only of plain
/// names (no `..`, no root, no drive prefix).
fn inside(rel: &Path) -> bool {
    rel.components()
        .all(|c| matches!(c, std::path::Component::Normal(_)))
}

/// The largest series file the report reads (bytes): a series holds a few numbers per score
/// time; anything larger is not one, and reading it would bound nothing.
pub const MAX_SERIES_BYTES: u64 = crate::read_limited::SERIES.cap;

/// Where a run's series file may be: `root/<case>/<scene>/<id>.json` (root = the summary's
/// `series/` directory), else the record's own relative path under `root` or under `root`'s
/// parent (root = the summary's directory). Only paths inside those folders: a record's
/// `series`, case or scene that would leave them (absolute, `..`) is ignored.
pub fn series_candidates(root: &Path, r: &Record) -> Vec<PathBuf> {
    let id = run_id(
        &r.key.param,
        &r.key.integrator,
        &r.key.formulation,
        r.dt,
        r.tol,
    );
    let mut out = vec![];
    let own = Path::new(&r.key.case)
        .join(&r.key.scene)
        .join(format!("{id}.json"));
    if inside(&own) && own.components().count() == 3 {
        out.push(root.join(own));
    }
    if let Some(rel) = r.series.as_deref().map(Path::new).filter(|p| inside(p)) {
        out.push(root.join(rel));
        if let Some(parent) = root.parent() {
            out.push(parent.join(rel));
        }
    }
    out
}

/// A run's series, if its file is a regular file of at most `MAX_SERIES_BYTES` and parses.
pub fn load_series(root: &Path, r: &Record) -> Option<Series> {
    series_candidates(root, r).into_iter().find_map(|p| {
        let bytes = crate::read_limited::read(&p, crate::read_limited::SERIES).ok()?;
        serde_json::from_slice(&bytes).ok()
    })
}

/// A stability record's series file `rel` under the folder `dir` of `stability.json`, as
/// JSON: None when `rel` would leave the folder (absolute, `..`), or the file is not a
/// regular file of at most `MAX_SERIES_BYTES`, or does not parse.
pub fn load_json_inside(dir: &Path, rel: &Path) -> Option<serde_json::Value> {
    if !inside(rel) {
        return None;
    }
    let bytes = crate::read_limited::read(&dir.join(rel), crate::read_limited::SERIES).ok()?;
    serde_json::from_slice(&bytes).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Numbers keep 3 significant digits and drop trailing zeros.
    #[test]
    fn number_format() {
        assert_eq!(num(0.01), "1e-2");
        assert_eq!(num(1.5e-7), "1.5e-7");
        assert_eq!(num(1.2345e-7), "1.23e-7");
        assert_eq!(num(12345.0), "12345");
        assert_eq!(num(0.5), "5e-1");
        assert_eq!(time(0.5), "0.5");
        assert_eq!(time(1.234567), "1.235");
        assert_eq!(time(20.0), "20");
        assert_eq!(time(0.0), "0");
        assert_eq!(time(3.2e-5), "3.2e-5");
    }

    /// Variants sort in registry order, not alphabetically.
    #[test]
    fn registry_order() {
        let k = |p: &str, i: &str| VariantKey {
            param: p.into(),
            integrator: i.into(),
            formulation: "body".into(),
        };
        assert!(k("euler_zyx", "rk4") < k("euler_zxz", "rk4"));
        assert!(k("so3", "rk4") < k("so3", "dopri5"));
        assert!(k("dual_quat", "euler") < k("zzz_unknown", "euler"));
    }
}
