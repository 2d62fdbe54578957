//! Convergence plots: the primary error against the fixed step (log-log), one line per
//! fixed-step variant, with the observed order `p` the suite fitted (summary `fits`: the
//! least-squares slope of log error against log step over the ladder points between 100x the
//! reference's accuracy claim and 1e-2; `n/a` with fewer than 3 such points) in the legend. A
//! method of order p shows a line of slope p in its asymptotic range; a flattening at small
//! steps is the reference or round-off floor.
//!
//! Adaptive variants have no step and are not drawn here (they are in the work-precision
//! plots). Failed runs are marked in the "failed" band at their step.
use super::chart::{FailMark, Legend, Line, Plot};
use super::data::{CaseView, SceneView, VariantRuns};
use super::select::{Admits, Panel, panels};
use crate::metrics::order::{ASYMPTOTIC_SPREAD, slope_spread};
use crate::problem::Axis;
use crate::summary::FitRecord;
use crate::summary::Status;

/// A fitted order with its fit quality: `p = 4.01 (local 3.98..4.05)`; `not asymptotic
/// (local slopes 0.2..4.1)` when the local slopes spread over more than
/// `ASYMPTOTIC_SPREAD` (the slope is then not an order and is not printed as one); `p n/a`
/// without an order.
pub fn fit_text(fit: Option<&FitRecord>) -> String {
    let Some(f) = fit else {
        return "p n/a".into();
    };
    let Some(p) = f.order else {
        return "p n/a".into();
    };
    match slope_spread(&f.points) {
        Some((spread, lo, hi)) if spread > ASYMPTOTIC_SPREAD => {
            format!("not asymptotic (local slopes {lo:.1}..{hi:.1})")
        }
        Some((_, lo, hi)) => format!("p = {p:.2} (local {lo:.2}..{hi:.2})"),
        None => format!("p = {p:.2}"),
    }
}

/// The legend text of a variant: the names that vary in the selection (the title names the
/// fixed one) and the fitted order with its fit quality (`fit_text`).
pub fn order_label(v: &VariantRuns, sel: &Panel) -> String {
    let p = fit_text(v.fit);
    let k = &v.key;
    let names: Vec<&str> = sel
        .sel
        .legend_axes
        .iter()
        .map(|a| match a {
            Axis::Param => k.param.as_str(),
            Axis::Integrator => k.integrator.as_str(),
            Axis::Formulation => k.formulation.as_str(),
        })
        .collect();
    format!("{}: {p}", names.join(" "))
}

/// The convergence plots of a scene: the fixed-step variants of each panel of each of the
/// family's convergence selections (panels without a fixed-step variant in the scene are
/// left out).
pub fn plots(cv: &CaseView, sv: &SceneView, footer: &str) -> Vec<Plot> {
    cv.family
        .figures
        .convergence
        .iter()
        .flat_map(|&sel| panels(sel, cv.family))
        .filter(|p| sv.variants.iter().any(|v| p.admits(v) && !v.adaptive))
        .map(|p| plot(cv, sv, &p, footer))
        .collect()
}

/// One convergence plot.
pub fn plot(cv: &CaseView, sv: &SceneView, sel: &Panel, footer: &str) -> Plot {
    let mut lines = vec![];
    let mut fails = vec![];
    for v in sv.variants.iter().filter(|v| sel.admits(v) && !v.adaptive) {
        let mut points = vec![];
        for r in &v.runs {
            let Some(dt) = r.dt else { continue };
            match r.status {
                Status::Ok => {
                    if let Some(Some(e)) = r.metrics.get(&cv.primary) {
                        points.push((dt, *e));
                    }
                }
                Status::Failed => fails.push(FailMark {
                    key: v.key.clone(),
                    x: dt,
                }),
                Status::NotApplicable => {}
            }
        }
        lines.push(Line {
            key: v.key.clone(),
            points,
            label: Some(order_label(v, sel)),
            marker_every: 1,
        });
    }
    Plot {
        id: format!("{}/conv_{}", sv.name, sel.id),
        title: format!(
            "{}/{}: {} vs step ({})",
            cv.name, sv.name, cv.primary, sel.short
        ),
        x_label: super::data::t_labels(cv, &sv.name).1.into(),
        y_label: super::data::error_label(cv, sv),
        x: super::axes::Scale::Log,
        y: super::axes::Scale::Log,
        lines,
        fails,
        legend: Legend::PerLine,
        caption: format!(
            "Convergence: {} against the fixed step. {} Adaptive methods are not drawn. p is \
             the observed order fitted by the suite (slope over the ladder points between 100x \
             the reference's accuracy claim and 1e-2; n/a with fewer than 3 such points); \
             local: the range of the slopes between consecutive points of the fit. A fit whose \
             local slopes differ by more than {ASYMPTOTIC_SPREAD} is not asymptotic and gives \
             no order.{}",
            cv.primary,
            sel.drawn(cv.family, false),
            super::data::reference_clause(sv)
        ),
        footer: footer.into(),
        round_off: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fit(order: Option<f64>, points: Vec<[f64; 2]>) -> FitRecord {
        FitRecord {
            key: crate::summary::RunKey::new("c", "s", "so3", "rk4", "body"),
            metric: "e".into(),
            order,
            reason: None,
            points,
        }
    }

    /// An order is printed with the range of its local slopes; a fit whose local slopes
    /// differ by more than `ASYMPTOTIC_SPREAD` is "not asymptotic" and prints no order.
    #[test]
    fn order_with_fit_quality() {
        let law: Vec<[f64; 2]> = [1e-2f64, 2e-2, 4e-2]
            .iter()
            .map(|h| [*h, h.powi(4)])
            .collect();
        let t = fit_text(Some(&fit(Some(4.0), law)));
        assert_eq!(t, "p = 4.00 (local 4.00..4.00)");
        let floor = vec![[1e-2, 1e-9], [2e-2, 1e-9], [4e-2, 1.6e-8]];
        let t = fit_text(Some(&fit(Some(2.0), floor)));
        assert!(
            t.starts_with("not asymptotic (local slopes 0.0..4.0)"),
            "{t}"
        );
        assert!(!t.contains("p ="));
        assert_eq!(fit_text(Some(&fit(None, vec![]))), "p n/a");
        assert_eq!(fit_text(None), "p n/a");
    }
}
