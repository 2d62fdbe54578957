//! Observed order of convergence over a step ladder (docs/schemas.md, summary.json `fits`): the least-squares
//! slope of `log(error)` against `log(dt)` over the ladder points whose error lies between
//! `100 x` the reference's accuracy claim (below it the reference, not the method, is
//! measured) and `1e-2` (above it the method is outside its asymptotic range). Fewer than 3
//! such points give no order, with the reason.
//!
//! Fit quality: the local slopes between consecutive points of the fit (by step) and their
//! spread (max - min). A method in its asymptotic range has local slopes close to its order;
//! a spread above [`ASYMPTOTIC_SPREAD`] says the points straddle a change of regime (round-off,
//! the reference floor, an unstable coarse step), and the least-squares slope is then not an
//! order (the report says "not asymptotic" instead of printing it).
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
    match loglog_slope(&used) {
        Some(order) => Fit {
            order: Some(order),
            reason: None,
            points: used,
        },
        None => Fit {
            order: None,
            reason: Some("all ladder points have the same step".into()),
            points: used,
        },
    }
}

/// The least-squares slope of `log y` against `log x` through `[x, y]` points (all positive
/// and finite); None for fewer than two points or when every `x` is the same.
pub fn loglog_slope(points: &[[f64; 2]]) -> Option<f64> {
    if points.len() < 2 || points.iter().any(|[x, y]| !(*x > 0.0 && *y > 0.0)) {
        return None;
    }
    let n = points.len() as f64;
    let (mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0);
    for [x, y] in points {
        let (x, y) = (x.ln(), y.ln());
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    let den = n * sxx - sx * sx;
    if den.abs() <= 1e-300 || den.is_nan() {
        return None;
    }
    let slope = (n * sxy - sx * sy) / den;
    slope.is_finite().then_some(slope)
}

/// The largest spread of local slopes for which a fitted slope is reported as an order.
pub const ASYMPTOTIC_SPREAD: f64 = 1.0;

/// The slopes of `log y` against `log x` between consecutive points sorted by `x` (points
/// that are not positive, or share an `x` with their neighbour, are skipped).
pub fn local_slopes(points: &[[f64; 2]]) -> Vec<f64> {
    let mut p: Vec<[f64; 2]> = points
        .iter()
        .copied()
        .filter(|[x, y]| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .collect();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]));
    p.windows(2)
        .filter(|w| w[1][0] > w[0][0])
        .map(|w| (w[1][1] / w[0][1]).ln() / (w[1][0] / w[0][0]).ln())
        .collect()
}

/// The spread (max - min) of the local slopes and their range; None with fewer than two
/// local slopes (a two-point fit has nothing to compare).
pub fn slope_spread(points: &[[f64; 2]]) -> Option<(f64, f64, f64)> {
    let s = local_slopes(points);
    if s.len() < 2 {
        return None;
    }
    let lo = s.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = s.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Some((hi - lo, lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The log-log slope of a power law is its exponent; degenerate inputs give none.
    #[test]
    fn loglog_slope_of_power_laws() {
        let pts: Vec<[f64; 2]> = [1.0, 10.0, 100.0, 1e4]
            .iter()
            .map(|k: &f64| [*k, 0.3 * k.powf(-0.5)])
            .collect();
        assert!((loglog_slope(&pts).unwrap() + 0.5).abs() < 1e-12);
        assert_eq!(loglog_slope(&pts[..1]), None);
        assert_eq!(loglog_slope(&[[2.0, 1.0], [2.0, 3.0]]), None);
        assert_eq!(loglog_slope(&[[1.0, 1.0], [2.0, 0.0]]), None);
    }

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

    /// The local slopes of a power law all equal its exponent (spread 0); a ladder that
    /// flattens onto a floor has a spread above `ASYMPTOTIC_SPREAD`, in any input order.
    #[test]
    fn local_slopes_and_spread() {
        let law: Vec<[f64; 2]> = [4e-2, 1e-2, 2e-2]
            .iter()
            .map(|h: &f64| [*h, 3.0 * h.powi(4)])
            .collect();
        let s = local_slopes(&law);
        assert_eq!(s.len(), 2);
        assert!(s.iter().all(|p| (p - 4.0).abs() < 1e-12), "{s:?}");
        let (spread, lo, hi) = slope_spread(&law).unwrap();
        assert!(spread < 1e-12 && (lo - 4.0).abs() < 1e-12 && (hi - 4.0).abs() < 1e-12);
        // 4th order, then flat at the floor: slopes 4 and 0.
        let floor = [[1e-2, 1e-9], [2e-2, 1e-9], [4e-2, 1.6e-8]];
        let (spread, lo, hi) = slope_spread(&floor).unwrap();
        assert!(spread > ASYMPTOTIC_SPREAD && lo.abs() < 1e-12 && (hi - 4.0).abs() < 1e-12);
        assert_eq!(slope_spread(&floor[..2]), None);
    }
}
