//! Chart diagnostics: `constraint_error_max`, the max over the samples of the chart's own
//! residual (`||q|^2 - 1|`, `|R^T R - I|`, the dual quaternion's two; absent for minimal
//! charts), and `conditioning_min`, the chart's minimum conditioning over every step of the run
//! (0 on its singular set; recorded for failed runs too, up to the failure).
use super::Scores;
use crate::run::RunOutput;

/// Scores the chart diagnostics.
pub fn score<O>(out: &RunOutput<O>, s: &mut Scores) {
    let mut any = false;
    let mut m = 0.0_f64;
    let mut finite = true;
    for smp in &out.samples {
        if let Some(r) = smp.residual {
            any = true;
            finite &= r.is_finite();
            m = m.max(r);
        }
    }
    if any {
        if finite {
            s.set("constraint_error_max", m);
        } else {
            s.null("constraint_error_max", "non-finite residual");
        }
    }
    if out.conditioning_min.is_finite() {
        s.set("conditioning_min", out.conditioning_min);
    } else {
        s.null("conditioning_min", "no state was checked");
    }
}
