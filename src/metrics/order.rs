//! Observed order of convergence over a step ladder (design.md, `fits`): the least-squares
//! slope of `log(error)` against `log(dt)` over the ladder points whose error lies between
//! `100 x` the reference's accuracy claim (below it the reference, not the method, is
//! measured) and `1e-2` (above it the method is outside its asymptotic range). Fewer than 3
//! such points give no order, with the reason.
use serde::Serialize;

/// A fitted order (or the reason there is none) and the points used.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fit {
    pub order: Option<f64>,
    pub reason: Option<String>,
    /// `[dt, error]` pairs used in the fit.
    pub points: Vec<[f64; 2]>,
}

/// Fits the order through the points of `(dt, error)` within `[floor, 1e-2]`.
pub fn fit(points: &[(f64, Option<f64>)], claim: f64) -> Fit {
    let floor = 100.0 * claim;
    let used: Vec<[f64; 2]> = points
        .iter()
        .filter_map(|(h, e)| e.map(|e| [*h, e]))
        .filter(|[h, e]| *h > 0.0 && e.is_finite() && *e >= floor && *e <= 1e-2)
        .collect();
    if used.len() < 3 {
        return Fit {
            order: None,
            reason: Some(format!(
                "{} of {} ladder points lie between 100x the reference claim ({floor:.1e}) and 1e-2",
                used.len(),
                points.len()
            )),
            points: used,
        };
    }
    let n = used.len() as f64;
    let (mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0);
    for [h, e] in &used {
        let (x, y) = (h.ln(), e.ln());
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    let den = n * sxx - sx * sx;
    if den.abs() < 1e-300 {
        return Fit {
            order: None,
            reason: Some("all ladder points have the same step".into()),
            points: used,
        };
    }
    Fit {
        order: Some((n * sxy - sx * sy) / den),
        reason: None,
        points: used,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pure power law is fitted exactly; points outside [100 claim, 1e-2] are excluded and
    /// fewer than three usable points give no order with a reason.
    #[test]
    fn power_law_and_window() {
        let pts: Vec<(f64, Option<f64>)> = [1e-1, 5e-2, 2.5e-2, 1.25e-2, 6.25e-3]
            .iter()
            .map(|h: &f64| (*h, Some(3.0 * h.powi(4))))
            .collect();
        let f = fit(&pts, 1e-14);
        // errors 3e-4, 1.9e-5, 1.2e-6, 7.3e-8, 4.6e-9: all inside [1e-12, 1e-2]
        assert_eq!(f.points.len(), 5);
        assert!((f.order.unwrap() - 4.0).abs() < 1e-12);
        let f = fit(&pts, 1e-9); // floor 1e-7: drops the smallest two
        assert_eq!(f.points.len(), 3);
        assert!((f.order.unwrap() - 4.0).abs() < 1e-12);
        let f = fit(&pts, 2e-8); // floor 2e-6: two points left
        assert!(f.order.is_none());
        assert!(f.reason.unwrap().contains("2 of 5"));
        let with_null = vec![(0.1, None), (0.05, Some(1e-3)), (0.025, Some(1e-4))];
        assert!(fit(&with_null, 1e-12).order.is_none());
    }
}
