//! Bring your own integrator: Ralston's third-order Runge-Kutta method, which the suite does
//! not have, written once as a factory over systems (`mbdbench::methods::FixedStepMethod`),
//! registered in a catalogue under its own name and run through the suite's own command line
//! (`cli::execute_with`): on every rigid chart and formulation and every flexible-beam ODE form,
//! scored against the same references, reported, ranked by `advise` and gated, as the built-in
//! methods are.
//!
//! Ralston's method (Ralston, Math. Comp. 16, 1962, the minimum-error-bound third-order
//! choice): `c = (0, 1/2, 3/4)`, `a21 = 1/2`, `a32 = 3/4`, `b = (2/9, 1/3, 4/9)`. On a Lie-group
//! chart each stage is taken as a Runge-Kutta-Munthe-Kaas stage (`System::rkmk_stage`: the
//! retraction of the stage increment and the `dexp_inv` correction), which keeps order 3.
//!
//! Run it as the suite's command line with the method added:
//!
//! ```text
//! cargo run --release --example byo_integrator -- run --quick --out target/byo
//! cargo run --release --example byo_integrator -- report --summary target/byo/summary.json
//! cargo run --release --example byo_integrator -- advise --summary target/byo/summary.json --json
//! ```
//!
//! With no arguments it runs the quick tier into `target/byo_integrator/run/` and reports,
//! advises and gates it there (what `.ci/run` does). The cases are the embedded ones with one
//! gate added for the new method (the overlay, written to `target/byo_integrator/cases/`).
use clap::Parser;
use mbdbench::catalogue::Catalogue;
use mbdbench::integrate::{Failure, FixedStep, MethodInfo, MethodKind, Stats, System};
use mbdbench::math::vector::Vector;
use mbdbench::methods::{Fixed, FixedStepMethod, Where};
use std::marker::PhantomData;

/// Ralston's third-order method, for every system.
pub struct Ralston3;

/// Ralston's method stepping systems of type `S` (it keeps no workspace).
pub struct Ralston3On<S>(PhantomData<S>);

impl<S: System> FixedStep<S> for Ralston3On<S> {
    fn info(&self) -> MethodInfo {
        MethodInfo::new("ralston3", MethodKind::Explicit, 3)
            .with_stages(3)
            .with_lie_group(S::LIE)
    }

    fn step(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &mut S::State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        let k1 = sys.rhs(t, x);
        let (_, _, k2) = sys.rkmk_stage(t + 0.5 * h, x, &k1.scaled(0.5 * h));
        let (_, _, k3) = sys.rkmk_stage(t + 0.75 * h, x, &k2.scaled(0.75 * h));
        stats.rhs_evals += 3;
        let mut dx = k1.scaled(2.0 / 9.0 * h);
        dx.axpy(h / 3.0, &k2);
        dx.axpy(4.0 / 9.0 * h, &k3);
        let next = sys.retract(x, &dx);
        sys.check(t + h, &next)?;
        *x = next;
        Ok(())
    }
}

impl FixedStepMethod for Ralston3 {
    type On<S: System> = Ralston3On<S>;
    fn on<S: System>(&self) -> Ralston3On<S> {
        Ralston3On(PhantomData)
    }
}

/// Where the example writes its case overlay and its run.
const OUT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/byo_integrator");

/// The gate written for Ralston's method: its rotation error on nine_spring's two_angles
/// scene, chart so3, body formulation, at the quick tier's 1e-2 s step (6.275e-4 rad when the
/// gate was written; RK4 gives 1.7e-6 there) may grow by 60 % before the gate fails.
const GATE: &str = r#"
[[gates]]
metric = "rotation_error_max"
max = 1.004e-3
baseline = 6.275e-4
margin = 1.6
where = { scene = "two_angles", param = "so3", integrator = "ralston3", formulation = "body", dt = 1.0e-2 }
quick = true
"#;

/// The case overlay: the embedded cases, nine_spring with the gate above appended, written
/// to `OUT/cases`.
pub fn overlay() -> std::io::Result<String> {
    let dir = format!("{OUT}/cases");
    std::fs::create_dir_all(&dir)?;
    for (label, text) in mbdbench::case::embedded_sources() {
        let name = std::path::Path::new(label)
            .file_name()
            .expect("a file name");
        let text = if name == "nine_spring.toml" {
            format!("{text}{GATE}")
        } else {
            text.to_string()
        };
        std::fs::write(std::path::Path::new(&dir).join(name), text)?;
    }
    Ok(dir)
}

/// The catalogue with Ralston's method registered, reading the case overlay.
fn catalogue(cases: &str) -> Catalogue {
    Catalogue::builtin()
        .with_method("ralston3", Where::Everywhere, Fixed(Ralston3))
        .expect("ralston3 is a new name")
        .with_cases(cases)
}

/// Runs one command line of the suite with the catalogue; its exit code.
pub fn command(cases: &str, args: &[&str]) -> i32 {
    let argv = std::iter::once("mbdbench").chain(args.iter().copied());
    match mbdbench::cli::Cli::try_parse_from(argv) {
        Ok(cli) => mbdbench::cli::execute_with(catalogue(cases), cli),
        Err(e) => {
            let _ = e.print();
            2
        }
    }
}

fn main() {
    mbdbench::output::interrupt::install();
    let cases = match overlay() {
        Ok(dir) => dir,
        Err(e) => {
            eprintln!("byo_integrator: cannot write the case overlay under {OUT}: {e}");
            std::process::exit(2);
        }
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    if !args.is_empty() {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        std::process::exit(command(&cases, &args));
    }
    let out = format!("{OUT}/run");
    let summary = format!("{out}/summary.json");
    for step in [
        vec!["run", "--quick", "--out", &out],
        vec!["report", "--summary", &summary],
        vec!["advise", "--summary", &summary],
        // The case the gate above was written in (the catalogue's other gates judge the new
        // method too: on the beam's quick ladder, 2.5e-3 s, Ralston's method diverges where
        // RK4 does not, its stability interval on the imaginary axis being shorter).
        vec![
            "gate",
            "--summary",
            &summary,
            "--quick",
            "--case",
            "nine_spring",
        ],
    ] {
        eprintln!("byo_integrator: mbdbench {}", step.join(" "));
        let code = command(&cases, &step);
        if code != 0 {
            eprintln!("byo_integrator: `{}` exited {code}", step.join(" "));
            std::process::exit(code);
        }
    }
}
