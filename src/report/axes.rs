//! Axis specifications with explicit tick positions and labels (set the log-axis key
//! points explicitly: plotters' default drops the end labels).
//!
//! Every plot is drawn in a *transformed* linear space: a log axis carries `log10(v)`, so a
//! decade is one unit and a tick at `k` is labelled `1e{k}`. The range of a log axis is
//! widened outward to whole decades (`floor(log10 min)` .. `ceil(log10 max)`), with a tick at
//! every decade, or every `s`-th decade when the span exceeds 10 decades (`s = ceil(span/10)`;
//! the lower end is moved down so both ends carry a labelled tick). Linear axes use "nice"
//! steps (1, 2, 2.5, 5 x 10^k, about 6 intervals) with both ends on a tick. A category axis
//! puts item `i` at `i` in `[-0.5, n - 0.5]`. Non-positive or non-finite values have no place
//! on a log axis (`map` returns None); callers drop them or pin them to an edge.
//!
//! An optional "failed" band above a log axis (one more tick interval) is where the plots
//! put runs that ended with a typed failure and therefore have no value.

/// How values map onto an axis.
#[derive(Debug, Clone, PartialEq)]
pub enum Scale {
    Log,
    Linear,
    /// Named items at 0, 1, ... (the x axis of the across-scene plots).
    Category(Vec<String>),
}

/// An axis: its range and ticks in transformed coordinates, and how to label them.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisSpec {
    pub scale: Scale,
    pub lo: f64,
    pub hi: f64,
    /// Labelled ticks (transformed), both ends included for log and linear axes.
    pub major: Vec<f64>,
    /// Light grid lines (transformed): 2..9 x 10^k on a log axis with a 1-decade stride.
    pub minor: Vec<f64>,
    /// The "failed" band, `(start, mark level)` (transformed); `hi` is its top.
    pub fail_band: Option<(f64, f64)>,
    /// Decimals of linear labels.
    decimals: usize,
}

impl AxisSpec {
    /// A log axis covering the positive finite `values` (None if there is none).
    pub fn log(values: impl IntoIterator<Item = f64>) -> Option<AxisSpec> {
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values {
            if v.is_finite() && v > 0.0 {
                min = min.min(v);
                max = max.max(v);
            }
        }
        if min > max {
            return None;
        }
        let mut e0 = min.log10().floor() as i32;
        let mut e1 = max.log10().ceil() as i32;
        if e1 <= e0 {
            e1 = e0 + 1;
        }
        let span = e1 - e0;
        let stride = if span <= 10 { 1 } else { (span + 9) / 10 };
        e0 -= (stride - span % stride) % stride;
        let major: Vec<f64> = (e0..=e1).step_by(stride as usize).map(f64::from).collect();
        let minor: Vec<f64> = if stride == 1 {
            (e0..e1)
                .flat_map(|k| (2..10).map(move |m| f64::from(k) + f64::from(m).log10()))
                .collect()
        } else {
            (e0..=e1)
                .filter(|k| (k - e0) % stride != 0)
                .map(f64::from)
                .collect()
        };
        Some(AxisSpec {
            scale: Scale::Log,
            lo: f64::from(e0),
            hi: f64::from(e1),
            major,
            minor,
            fail_band: None,
            decimals: 0,
        })
    }

    /// A linear axis covering the finite `values` (None if there is none).
    pub fn linear(values: impl IntoIterator<Item = f64>) -> Option<AxisSpec> {
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values {
            if v.is_finite() {
                min = min.min(v);
                max = max.max(v);
            }
        }
        if min > max {
            return None;
        }
        let raw = if max > min {
            (max - min) / 6.0
        } else {
            min.abs().max(1.0) / 6.0
        };
        let k = raw.log10().floor();
        let base = 10f64.powf(k);
        let m = raw / base;
        let (mant, extra) = if m <= 1.0 {
            (1.0, 0)
        } else if m <= 2.0 {
            (2.0, 0)
        } else if m <= 2.5 {
            (2.5, 1)
        } else if m <= 5.0 {
            (5.0, 0)
        } else {
            (10.0, 0)
        };
        let step = mant * base;
        let i0 = (min / step).floor() as i64;
        let mut i1 = (max / step).ceil() as i64;
        if i1 <= i0 {
            i1 = i0 + 1;
        }
        let major = (i0..=i1).map(|i| i as f64 * step).collect();
        let decimals = (-(step.log10().floor()) as i64 + extra).max(0) as usize;
        Some(AxisSpec {
            scale: Scale::Linear,
            lo: i0 as f64 * step,
            hi: i1 as f64 * step,
            major,
            minor: vec![],
            fail_band: None,
            decimals,
        })
    }

    /// A category axis with the given item names.
    pub fn category(names: Vec<String>) -> AxisSpec {
        let n = names.len().max(1);
        AxisSpec {
            major: (0..names.len()).map(|i| i as f64).collect(),
            scale: Scale::Category(names),
            lo: -0.5,
            hi: n as f64 - 0.5,
            minor: vec![],
            fail_band: None,
            decimals: 0,
        }
    }

    /// Adds the "failed" band on top: one more tick interval, its middle labelled `failed`.
    pub fn with_fail_band(mut self) -> AxisSpec {
        let stride = match self.major.as_slice() {
            [.., a, b] => b - a,
            _ => 1.0,
        };
        let start = self.hi;
        let mark = start + 0.5 * stride;
        self.hi = start + stride;
        self.major.push(mark);
        self.fail_band = Some((start, mark));
        self
    }

    /// The transformed coordinate of a value (None: not representable, e.g. `v <= 0` on a log
    /// axis).
    pub fn map(&self, v: f64) -> Option<f64> {
        match self.scale {
            Scale::Log if v.is_finite() && v > 0.0 => Some(v.log10()),
            Scale::Log => None,
            _ if v.is_finite() => Some(v),
            _ => None,
        }
    }

    /// The label of a tick at transformed coordinate `t`.
    pub fn label(&self, t: f64) -> String {
        if let Some((_, mark)) = self.fail_band
            && (t - mark).abs() < 1e-9
        {
            return "failed".into();
        }
        match &self.scale {
            Scale::Log => {
                let e = t.round() as i32;
                if e == 0 { "1".into() } else { format!("1e{e}") }
            }
            Scale::Linear => format!("{t:.*}", self.decimals),
            Scale::Category(names) => {
                let i = t.round();
                if i >= 0.0 && (i as usize) < names.len() && (t - i).abs() < 1e-9 {
                    names[i as usize].clone()
                } else {
                    String::new()
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A log axis spans whole decades and labels both ends (the end labels plotters drops).
    #[test]
    fn log_axis_labels_both_ends() {
        let a = AxisSpec::log([3.2e-7, 4.0e-3, 0.0, f64::NAN]).unwrap();
        assert_eq!((a.lo, a.hi), (-7.0, -2.0));
        assert_eq!(a.major.first(), Some(&-7.0));
        assert_eq!(a.major.last(), Some(&-2.0));
        assert_eq!(a.label(-7.0), "1e-7");
        assert_eq!(a.label(-2.0), "1e-2");
        assert_eq!(a.label(0.0), "1");
        // 8 minor lines per decade for 5 decades.
        assert_eq!(a.minor.len(), 40);
        assert_eq!(a.map(0.0), None);
        assert!((a.map(1e-3).unwrap() + 3.0).abs() < 1e-12);
    }

    /// A wide log axis uses a stride and still ends on labelled ticks.
    #[test]
    fn wide_log_axis_stride() {
        let a = AxisSpec::log([1e-17, 1e4]).unwrap();
        // 21 decades: stride ceil(21 / 10) = 3, which divides 21: ticks -17, -14, ..., 4.
        assert_eq!(a.hi, 4.0);
        assert_eq!(a.lo, -17.0);
        assert_eq!(a.major.len(), 8);
        // 13 decades: stride 2, lower end moved from -9 to -10 so that 14 = 7 x 2.
        let w = AxisSpec::log([2e-9, 5e3]).unwrap();
        assert_eq!((w.lo, w.hi), (-10.0, 4.0));
        assert_eq!(w.major.len(), 8);
        assert_eq!(a.major.first(), Some(&a.lo));
        assert_eq!(a.major.last(), Some(&a.hi));
        // A single value still gets one decade.
        let b = AxisSpec::log([1e-3]).unwrap();
        assert_eq!((b.lo, b.hi), (-3.0, -2.0));
    }

    /// A linear axis ends on nice ticks that cover the data.
    #[test]
    fn linear_axis_nice_ends() {
        let a = AxisSpec::linear([0.0, 3.2]).unwrap();
        assert_eq!(a.lo, 0.0);
        assert!(a.hi >= 3.2);
        assert_eq!(a.major.last(), Some(&a.hi));
        assert_eq!(a.major, vec![0.0, 1.0, 2.0, 3.0, 4.0]);
        assert_eq!(a.label(3.0), "3");
        let h = AxisSpec::linear([0.0, 1.5]).unwrap();
        assert_eq!(h.label(0.25), "0.25");
        let b = AxisSpec::linear([0.0, 20.0]).unwrap();
        assert_eq!(b.major.last(), Some(&20.0));
        assert_eq!(b.label(20.0), "20");
    }

    /// The failed band adds one interval on top, labelled `failed` in its middle.
    #[test]
    fn fail_band() {
        let a = AxisSpec::log([1e-6, 1e-2]).unwrap().with_fail_band();
        assert_eq!(a.hi, -1.0);
        assert_eq!(a.fail_band, Some((-2.0, -1.5)));
        assert_eq!(a.label(-1.5), "failed");
        assert_eq!(a.label(-2.0), "1e-2");
        let c = AxisSpec::category(vec!["a".into(), "b".into()]);
        assert_eq!((c.lo, c.hi), (-0.5, 1.5));
        assert_eq!(c.label(1.0), "b");
    }
}
