//! `mbdbench trajectory`: one run of one variant at one step or tolerance, its samples
//! written as named columns to one JSON file (docs/schemas.md, "Trajectory files"); a typed failure
//! keeps the samples up to it and exits 1, bad input exits 2 and writes nothing (a `--dt` or
//! `--t-end` whose run would take more than the case's `max_steps` is bad input in every
//! family).
use super::*;

pub(super) fn cmd_trajectory(common: &Common, a: &TrajectoryArgs) -> Result<i32, String> {
    let cases = load_cases(common)?;
    let mut p = compile_scene(common, &cases, a)?;
    let family = p.family();
    check_axis_names(family, a)?;
    let (param, formulation, v) = choose_variant(&*p, family, a)?;
    let (stepping, value) = choose_stepping(a, v)?;
    fit_run_to_case(&mut *p, &cases, a, v, value)?;
    let out = p.run(v, stepping, Want::Trajectory)?;
    let (doc, step_key, step) =
        trajectory_document(a, family, &param, &formulation, stepping, &out)?;
    write_trajectory(&a.out, doc)?;
    Ok(announce(a, out, &param, &formulation, step_key, step))
}

/// The compiled problem of `--case`'s `--scene`, refusing a scene the case does not have.
fn compile_scene(
    common: &Common,
    cases: &[Case],
    a: &TrajectoryArgs,
) -> Result<Box<dyn problem::Problem>, String> {
    if let Some(c) = cases.iter().find(|c| c.name == a.case)
        && c.scene(&a.scene).is_none()
    {
        let known: Vec<&str> = c.scenes.iter().map(|s| s.name.as_str()).collect();
        return Err(format!(
            "--scene {}: not a scene of case {} (its scenes: {})",
            a.scene,
            a.case,
            known.join(", ")
        ));
    }
    common
        .catalogue()
        .problems(
            cases,
            std::slice::from_ref(&a.case),
            std::slice::from_ref(&a.scene),
        )?
        .into_iter()
        .find(|p| p.case() == a.case && p.scene() == a.scene)
        .ok_or_else(|| format!("--scene {}: not in case {}", a.scene, a.case))
}

/// Refuses an unknown name on an axis with the family's valid names, as `run` does.
fn check_axis_names(family: &Family, a: &TrajectoryArgs) -> Result<(), String> {
    for (flag, name, valid) in [
        ("--param", a.param.as_deref(), family.axes.params),
        (
            "--integrator",
            Some(a.integrator.as_str()),
            family.axes.integrators,
        ),
        (
            "--formulation",
            a.formulation.as_deref(),
            family.axes.formulations,
        ),
    ] {
        if let Some(n) = name
            && !valid.contains(&n)
        {
            return Err(format!(
                "{flag} {n}: not a name of the {} family (valid: {})",
                family.model,
                valid.join(", ")
            ));
        }
    }
    Ok(())
}

/// The parameter, the formulation (the family's first by default) and their registered
/// variant, refused when it is not registered or is n/a on this problem.
fn choose_variant(
    p: &dyn problem::Problem,
    family: &Family,
    a: &TrajectoryArgs,
) -> Result<(String, String, &'static problem::Variant), String> {
    let param = match (&a.param, family.axes.params) {
        (Some(x), _) => x.clone(),
        (None, ["none"]) => "none".into(),
        (None, _) => {
            return Err(format!(
                "give --param: the {} family has {}",
                family.model,
                family.axes.params.join(", ")
            ));
        }
    };
    let formulation = a
        .formulation
        .clone()
        .unwrap_or_else(|| family.axes.formulations[0].to_string());
    let v = family
        .find(&param, &a.integrator, &formulation)
        .ok_or_else(|| {
            format!(
                "{param}/{}/{formulation}: not a registered variant ({})",
                a.integrator,
                (family.static_na_reason)(&param, &a.integrator, &formulation)
            )
        })?;
    if let Some(r) = p.na_reason(v) {
        return Err(format!(
            "{param}/{}/{formulation} is n/a here: {r}",
            a.integrator
        ));
    }
    Ok((param, formulation, v))
}

/// The stepping `--dt` or `--tol` gives the variant (the one its method takes) and its value,
/// which must be a positive number.
fn choose_stepping(a: &TrajectoryArgs, v: &problem::Variant) -> Result<(Stepping, f64), String> {
    let stepping = match (a.dt, a.tol, v.info.adaptive) {
        (Some(h), None, false) => Stepping::Dt(h),
        (None, Some(t), true) => Stepping::Tol(t),
        (Some(_), _, true) => {
            return Err(format!(
                "{} is adaptive: give --tol, not --dt",
                a.integrator
            ));
        }
        (_, Some(_), false) => {
            return Err(format!(
                "{} is a fixed-step method: give --dt, not --tol",
                a.integrator
            ));
        }
        _ => return Err("give --dt or --tol".into()),
    };
    let value = match stepping {
        Stepping::Dt(x) | Stepping::Tol(x) => x,
    };
    if !(value.is_finite() && value > 0.0) {
        return Err(format!("--dt/--tol {value}: must be a positive number"));
    }
    Ok((stepping, value))
}

/// Sets `--t-end` on the problem, and refuses a fixed step that does not divide
/// `score_every` or whose run would exceed the case's step budget.
fn fit_run_to_case(
    p: &mut dyn problem::Problem,
    cases: &[Case],
    a: &TrajectoryArgs,
    v: &problem::Variant,
    value: f64,
) -> Result<(), String> {
    if let Some(t) = a.t_end {
        if !(t.is_finite() && t > 0.0) {
            return Err(format!("--t-end {t}: must be a positive number"));
        }
        check_t_end(t, &*p)?;
        p.set_t_end(t);
    }
    if !v.info.adaptive && crate::run::divides(p.score_every(), value).is_none() {
        return Err(format!(
            "--dt {value}: does not divide score_every = {} (cases/README.md, \"Conventions\")",
            p.score_every()
        ));
    }
    if !v.info.adaptive
        && let Some(c) = cases.iter().find(|c| c.name == a.case)
        && let Some(s) = c.scene(&a.scene)
        && let Some(why) = case::budget::over_step_budget(c, s, p.t_end(), value)
    {
        return Err(format!("--dt {value}: {why}"));
    }
    Ok(())
}

/// The trajectory file's fields (names, step or tolerance, units, status, failure, columns),
/// with the step's key (`dt` or `tol`) and value.
fn trajectory_document<'a>(
    a: &'a TrajectoryArgs,
    family: &Family,
    param: &'a str,
    formulation: &'a str,
    stepping: Stepping,
    out: &'a problem::Outcome,
) -> Result<(BTreeMap<&'a str, Field<'a>>, &'static str, f64), String> {
    let mut doc: BTreeMap<&str, Field> = BTreeMap::new();
    for (k, x) in [
        ("case", a.case.as_str()),
        ("scene", &a.scene),
        ("param", param),
        ("integrator", &a.integrator),
        ("formulation", formulation),
        ("git_commit", crate::summary::git_commit()),
    ] {
        doc.insert(k, Field::Value(x.into()));
    }
    // The step or tolerance the run took, and each column's unit.
    let (step_key, step) = match stepping {
        Stepping::Dt(h) => ("dt", h),
        Stepping::Tol(t) => ("tol", t),
    };
    doc.insert(step_key, Field::Value(step.into()));
    let units: serde_json::Map<String, serde_json::Value> = family
        .columns
        .iter()
        .map(|c| (c.name.to_string(), c.unit.into()))
        .collect();
    doc.insert("units", Field::Value(units.into()));
    let status = if out.failure.is_some() {
        "failed"
    } else {
        "ok"
    };
    doc.insert("status", Field::Value(status.into()));
    doc.insert(
        "failure",
        Field::Value(serde_json::to_value(&out.failure).map_err(|e| e.to_string())?),
    );
    if let Some(cols) = &out.columns {
        doc.insert("t", Field::Numbers(&cols.t, 1));
        for (name, width, values) in &cols.columns {
            doc.insert(name, Field::Numbers(values, *width));
        }
    }
    Ok((doc, step_key, step))
}

/// Writes the document to `--out` in one step (nothing partial on an error).
fn write_trajectory(path: &std::path::Path, doc: BTreeMap<&str, Field>) -> Result<(), String> {
    reference::write_atomic_with(path, |w| {
        serde_json::to_writer(w, &doc).map_err(std::io::Error::from)
    })
    .map_err(|e| format!("{}: {e}", path.display()))
}

/// Says what was written, tells a failed run's failure, and returns the exit status.
fn announce(
    a: &TrajectoryArgs,
    out: problem::Outcome,
    param: &str,
    formulation: &str,
    step_key: &str,
    step: f64,
) -> i32 {
    let samples = out.columns.as_ref().map_or(0, |c| c.t.len());
    crate::say!(
        "trajectory: {} ({samples} samples of {}/{}/{param}/{}/{formulation} at {step_key} = \
         {step:e})",
        a.out.display(),
        a.case,
        a.scene,
        a.integrator
    );
    if let Some(f) = out.failure {
        crate::tell!(
            "run failed: {} at t = {}: {}",
            f.kind.name(),
            f.t,
            f.message
        );
        return EXIT_FAILED;
    }
    EXIT_OK
}

/// One field of the trajectory file: a value, or samples of `width` numbers each, written
/// flat (`width` 1) or one list per sample. The document is serialised straight into the file
/// from the run's columns, in the order and form of the map of values it replaces (the same
/// bytes), without building that map: its values took about 75 bytes a number (550 MB for
/// 5e5 rigid-body samples, against 120 bytes a sample in the columns).
enum Field<'a> {
    Value(serde_json::Value),
    Numbers(&'a [f64], usize),
}

impl serde::Serialize for Field<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Field::Value(v) => v.serialize(s),
            Field::Numbers(x, 1) => x.serialize(s),
            Field::Numbers(x, width) => s.collect_seq(x.chunks(*width)),
        }
    }
}
