//! The sensitivity part: the growth `G(t)` of a perturbation of each scene's initial state
//! from its series file, the predictable horizon in the legend.
use super::*;

pub(super) fn is_sensitivity(r: &Record) -> bool {
    r.metrics.contains_key("sensitivity_growth_max")
}

/// The growth series of a sensitivity record: `(t, G(t))`.
pub(super) fn load_growth(dir: &Path, r: &Record) -> Option<Vec<(f64, f64)>> {
    let rel = r.series.as_ref()?;
    let v = crate::report::data::load_json_inside(dir, Path::new(rel))?;
    let (t, g) = (column(&v, "t")?, column(&v, "growth")?);
    Some(t.into_iter().zip(g).collect())
}

/// The sensitivity plot of a case: the growth `G(t)` of a 1e-9 perturbation of each scene's
/// initial state against t (log y), one line per scene.
pub(super) fn sensitivity_plot(
    case: &str,
    rs: &[&Record],
    dir: &Path,
    footer: &str,
) -> Option<Plot> {
    let rs: Vec<&Record> = rs.iter().copied().filter(|r| is_sensitivity(r)).collect();
    if rs.is_empty() {
        return None;
    }
    let mut lines = vec![];
    let mut missing = vec![];
    for r in &rs {
        let Some(points) = load_growth(dir, r) else {
            missing.push(r.key.scene.clone());
            continue;
        };
        let points: Vec<(f64, f64)> = points.into_iter().filter(|p| p.1 > 0.0).collect();
        let n = points.len();
        let horizon = r.metrics.get("predictable_horizon").copied().flatten();
        lines.push(Line {
            key: VariantKey {
                param: "so3".into(),
                integrator: r.key.scene.clone(),
                formulation: "body".into(),
            },
            points,
            label: Some(match horizon {
                Some(h) => format!("{} (predictable to t = {})", r.key.scene, num(h)),
                None => r.key.scene.clone(),
            }),
            marker_every: (n / 8).max(1),
        });
    }
    let mut caption = format!(
        "How far each scene carries a 1e-9 change of its initial state: G(t), the largest \
         singular value of the finite-difference state-transition matrix (the growth of the \
         worst initial direction of attitude, position, velocity and rate), against t \
         (dop853/so3/body at tol {}). Where G passes 1e7 a round-off-sized difference has grown \
         past 1e-9, so errors below 1e-9 measured beyond that time (the predictable horizon in \
         the legend) say nothing about a method.",
        num(crate::model::rigid_body::stability::sensitivity::TOL)
    );
    if !missing.is_empty() {
        caption.push_str(&format!(" No series file for: {}.", missing.join(", ")));
    }
    Some(Plot {
        id: "stability/sensitivity".into(),
        title: format!("{case}: growth of a 1e-9 initial perturbation"),
        x_label: "t (s)".into(),
        y_label: "growth G(t)".into(),
        x: Scale::Linear,
        y: Scale::Log,
        ..Plot::per_line(lines, caption, footer)
    })
}
