//! The stiffness ladder's part: log-log step against the stiffness factor, one line per
//! variant through its fit's measured points with the slope in the legend; capped and null
//! points are not measurements and are named in the caption.
use super::*;

/// The record scenes of a ladder fit scene: `two_angles_stiffness[_T10]` ->
/// `two_angles_k1e<j>[_T10]` with their factors `10^j`.
pub(super) fn ladder_records<'a>(
    fit_scene: &str,
    records: &[&'a Record],
) -> Vec<(f64, &'a Record)> {
    let Some((base, suffix)) = fit_scene.split_once("_stiffness") else {
        return vec![];
    };
    let head = format!("{base}_k1e");
    records
        .iter()
        .filter_map(|r| {
            let rest = r.key.scene.strip_prefix(&head)?.strip_suffix(suffix)?;
            let j: i32 = rest.parse().ok()?;
            Some((10f64.powi(j), *r))
        })
        .collect()
}

/// The stiffness-ladder plots of a case: one per fit scene and metric.
pub(super) fn ladder_plots(
    case: &str,
    fits: &[&FitRecord],
    records: &[&Record],
    footer: &str,
) -> Vec<Plot> {
    let mut groups: BTreeMap<(bool, String, usize, String), Vec<&FitRecord>> = BTreeMap::new();
    for f in fits.iter().filter(|f| is_ladder_fit(f)) {
        let base = f.metric.trim_end_matches("_vs_stiffness").to_string();
        let accurate = usize::from(base.contains("accurate"));
        groups
            .entry((
                f.key.scene.ends_with("_T10"),
                f.key.scene.clone(),
                accurate,
                base,
            ))
            .or_default()
            .push(f);
    }
    let mut out = vec![];
    for ((fixed, scene, _, metric), mut fs) in groups {
        fs.sort_by_key(|f| VariantKey::of(&f.key));
        let rs = ladder_records(&scene, records);
        let mut lines = vec![];
        let mut unmeasured: Vec<String> = vec![];
        for f in &fs {
            let key = VariantKey::of(&f.key);
            let slope = match f.order {
                Some(p) => format!("slope {}", decimals(p, 2)),
                None => "slope - (too few points)".into(),
            };
            // Points the fit left out: capped (a lower bound) or null (nothing passed).
            let mut skipped: BTreeMap<String, Vec<String>> = BTreeMap::new();
            let mut mine: Vec<(f64, &Record)> = rs
                .iter()
                .filter(|(_, r)| VariantKey::of(&r.key) == key)
                .copied()
                .collect();
            mine.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (k, r) in mine {
                let why = r
                    .metric_reasons
                    .get(&metric)
                    .map(String::as_str)
                    .unwrap_or("");
                let what = match r.metrics.get(&metric).copied().flatten() {
                    Some(_) if capped(why) => "bounded up to the cap".to_string(),
                    Some(_) => continue,
                    None => short_reason(why),
                };
                skipped.entry(what).or_default().push(num(k));
            }
            for (what, ks) in skipped {
                unmeasured.push(format!("{} at k x {}: {what}", key.label(), ks.join(", ")));
            }
            let points: Vec<(f64, f64)> = f.points.iter().map(|p| (p[0], p[1])).collect();
            if points.is_empty() {
                continue;
            }
            lines.push(Line {
                key: key.clone(),
                points,
                label: Some(format!("{} / {}: {slope}", key.param, key.integrator)),
                marker_every: 1,
            });
        }
        let horizon = if fixed {
            "a fixed 10 s horizon".to_string()
        } else {
            "t_h in periods of the fastest mode (t_h shrinks as k^(-1/2))".to_string()
        };
        let what = metric.replace('_', " ");
        let mut caption = format!(
            "The {what} of each variant against the stiffness factor k (every spring of \
             nine_spring/two_angles times k), over {horizon}; lines join the points the \
             log-log slope was fitted on (slope in the legend; -1/2: limited by w h, -1: by \
             w^2 h t_h)."
        );
        if unmeasured.is_empty() {
            caption.push_str(" Every ladder point was measured.");
        } else {
            caption.push_str(&format!(
                " Not drawn (no measured step, not in the fit): {}.",
                unmeasured.join("; ")
            ));
        }
        let y_label = if metric.ends_with("_dt") {
            format!("{what} (s)")
        } else {
            what.clone()
        };
        let short_scene = if fixed { "10 s" } else { "t_h periods" };
        out.push(Plot {
            id: format!("stability/{scene}_{metric}"),
            title: format!("{case}: {what} vs stiffness ({short_scene})"),
            x_label: "stiffness factor k".into(),
            y_label,
            x: Scale::Log,
            y: Scale::Log,
            ..Plot::per_line(lines, caption, footer)
        });
    }
    out
}
