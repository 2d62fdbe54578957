//! Tests of the reinforced-concrete column under the cyclic displacement protocol against the
//! stored OpenSees runs of the same column (`references/fiber_column/opensees/`).
use nalgebra::DVector;

use super::basic::{Basic, DispBased, ForceBased};
use super::column::Column;
use super::layout::{Layer, Patch, fiber_section};
use super::material::{
    Concrete01, Concrete01Params, Concrete02, Concrete02Params, Material, Steel01, Steel01Params,
    Steel02, Steel02Params,
};
use super::section::Section;
use crate::rotation::{RotationChart, So3};
use crate::structural::equilibrium::{Equilibrium, Newton, NewtonLineSearch};
use crate::structural::krylov_newton::KrylovNewton;
use crate::structural::path::{PathFailure, Prescribed};

pub(super) const H: f64 = 3.0;
pub(super) const P: f64 = 750e3;
const GJ: f64 = 1.0e8;

/// The column's section with the `_c01` (`second = false`) or `_c02` materials: core 16 x 2
/// fibers, top and bottom covers 2 x 2, side covers 16 x 1, bars 4 + 4 + 2.
fn section(second: bool) -> Section {
    let (core, cover, steel) = if second {
        (
            Material::from(
                Concrete02::new(Concrete02Params {
                    fpc: -36e6,
                    epsc0: -0.004,
                    fpcu: -7.2e6,
                    epscu: -0.02,
                    lambda: 0.1,
                    ft: 3e6,
                    ets: 1.5e9,
                })
                .unwrap(),
            ),
            Material::from(
                Concrete02::new(Concrete02Params {
                    fpc: -30e6,
                    epsc0: -0.002,
                    fpcu: -6e6,
                    epscu: -0.006,
                    lambda: 0.1,
                    ft: 3e6,
                    ets: 1.5e9,
                })
                .unwrap(),
            ),
            Material::from(
                Steel02::new(Steel02Params {
                    fy: 420e6,
                    e0: 200e9,
                    b: 0.01,
                    r0: 18.0,
                    c_r1: 0.925,
                    c_r2: 0.15,
                })
                .unwrap(),
            ),
        )
    } else {
        (
            Material::from(
                Concrete01::new(Concrete01Params {
                    fpc: -36e6,
                    epsc0: -0.004,
                    fpcu: -30e6,
                    epscu: -0.014,
                })
                .unwrap(),
            ),
            Material::from(
                Concrete01::new(Concrete01Params {
                    fpc: -30e6,
                    epsc0: -0.002,
                    fpcu: 0.0,
                    epscu: -0.006,
                })
                .unwrap(),
            ),
            Material::from(
                Steel01::new(Steel01Params {
                    fy: 420e6,
                    e0: 200e9,
                    b: 0.01,
                })
                .unwrap(),
            ),
        )
    };
    let patch = |name: &str, m, y: [f64; 2], z: [f64; 2], ny, nz| Patch {
        name: name.into(),
        material: m,
        y,
        z,
        ny,
        nz,
    };
    let patches = [
        patch("core", core, [-0.21, 0.21], [-0.21, 0.21], 16, 2),
        patch("top", cover, [0.21, 0.25], [-0.25, 0.25], 2, 2),
        patch("bottom", cover, [-0.25, -0.21], [-0.25, 0.25], 2, 2),
        patch("side+", cover, [-0.21, 0.21], [0.21, 0.25], 16, 1),
        patch("side-", cover, [-0.21, 0.21], [-0.25, -0.21], 16, 1),
    ];
    let layer = |name: &str, y: f64, n| Layer {
        name: name.into(),
        material: steel,
        y: [y, y],
        z: [-0.21, 0.21],
        n,
        area: 4.91e-4,
    };
    let layers = [
        layer("top", 0.21, 4),
        layer("bottom", -0.21, 4),
        layer("mid", 0.0, 2),
    ];
    Section::Fiber(fiber_section(0.5, 0.5, &patches, &layers).unwrap())
}

/// The RC column in `elements` force-based (5 Lobatto points) or displacement-based (5
/// Legendre points) elements.
pub(super) fn rc_column<C: RotationChart>(
    second: bool,
    elements: usize,
    force_based: bool,
) -> Column<C> {
    let s = section(second);
    let h = H / elements as f64;
    let els = (0..elements)
        .map(|_| {
            if force_based {
                Basic::Force(Box::new(ForceBased::new(h, GJ, &s, 5, 1e-16, 50).unwrap()))
            } else {
                Basic::Disp(DispBased::new(h, GJ, &s, 5).unwrap())
            }
        })
        .collect();
    Column::new(H, els).unwrap()
}

/// The protocol's top displacement after each 0.5 mm step.
fn protocol() -> Vec<f64> {
    let mut out = vec![];
    let mut u = 0i64; // half-millimetres
    for amp_mm in [7.5, 15.0, 30.0, 45.0, 60.0, 90.0, 120.0] {
        let a = (amp_mm * 2.0f64).round() as i64;
        for _ in 0..2 {
            for target in [a, -a, 0] {
                while u != target {
                    u += (target - u).signum();
                    out.push(u as f64 * 0.5e-3);
                }
            }
        }
    }
    out
}

struct Run {
    shear: Vec<f64>,
    top: Vec<f64>,
    axial: Vec<f64>,
    iterations: usize,
    element_iterations: u64,
    subdivisions: u64,
    seconds: f64,
    /// The step (1-based) that failed and why.
    failure: Option<(usize, PathFailure)>,
}

fn run_cyclic<C: RotationChart, E: Equilibrium<Column<C>>>(
    second: bool,
    elements: usize,
    force_based: bool,
    mut algorithm: E,
) -> Run {
    let mut col: Column<C> = rc_column(second, elements, force_based);
    let mut f = DVector::zeros(col.dim());
    let tol = 1e-20;
    for k in 1..=10 {
        f[col.top_dof(2)] = -P * k as f64 / 10.0;
        col.step(&mut Newton::new(tol, 50).unwrap(), &f, None)
            .unwrap();
    }
    let start = std::time::Instant::now();
    let mut out = Run {
        shear: vec![],
        top: vec![],
        axial: vec![],
        iterations: 0,
        element_iterations: 0,
        subdivisions: 0,
        seconds: 0.0,
        failure: None,
    };
    let dof = col.top_dof(0);
    for (k, u) in protocol().into_iter().enumerate() {
        let (c, base) = match col.step(&mut algorithm, &f, Some(Prescribed { dof, value: u })) {
            Ok(x) => x,
            Err(e) => {
                out.failure = Some((k + 1, e));
                break;
            }
        };
        out.iterations += c.iterations;
        out.element_iterations += c.element_iterations;
        out.subdivisions += c.element_subdivisions;
        out.shear.push(-base.x);
        out.top.push(col.top_displacement().x);
        out.axial.push(col.top_displacement().z);
    }
    out.seconds = start.elapsed().as_secs_f64();
    out
}

pub(super) fn reference(scene: &str) -> serde_json::Value {
    let path = format!(
        "{}/references/fiber_column/opensees/{scene}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

pub(super) fn reference_column(r: &serde_json::Value, name: &str) -> Vec<f64> {
    r["data"][name]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// `int V du + P dv` by the trapezoid rule (v the shortening), from rest.
fn dissipated(shear: &[f64], top: &[f64], axial: &[f64]) -> f64 {
    let mut w = 0.0;
    for k in 1..shear.len() {
        w += 0.5 * (shear[k] + shear[k - 1]) * (top[k] - top[k - 1]);
        w += P * -(axial[k] - axial[k - 1]);
    }
    w
}

fn compare<E: Equilibrium<Column<So3>>>(scene: &str, second: bool, algorithm: E) -> Run {
    let name = E::NAME;
    let r = reference(scene);
    let run = run_cyclic::<So3, E>(second, 1, true, algorithm);
    if let Some((k, e)) = &run.failure {
        eprintln!("{scene} ({name}): step {k} failed: {e}");
    }
    // Reference rows: 0 is the state after the axial prelude, row k after step k.
    let v_ref = reference_column(&r, "base_shear");
    let u_ref = reference_column(&r, "top_displacement");
    let a_ref = reference_column(&r, "top_axial");
    let peak = v_ref.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut sq = 0.0;
    let mut worst = 0.0f64;
    for (k, v) in run.shear.iter().enumerate() {
        let d = v - v_ref[k + 1];
        sq += d * d;
        worst = worst.max(d.abs());
    }
    let rms = (sq / run.shear.len() as f64).sqrt() / peak;
    if let Some(k) =
        (0..run.shear.len()).find(|&k| (run.shear[k] - v_ref[k + 1]).abs() > 1e-9 * peak)
    {
        eprintln!(
            "{scene} ({name}): first departure beyond 1e-9 of the peak at step {} ({:e} of peak)",
            k + 1,
            (run.shear[k] - v_ref[k + 1]) / peak
        );
    }
    let mut shear = vec![v_ref[0]];
    shear.extend(&run.shear);
    let mut top = vec![0.0];
    top.extend(&run.top);
    let mut axial = vec![a_ref[0]];
    axial.extend(&run.axial);
    let w = dissipated(&shear, &top, &axial);
    let n = shear.len();
    let w_ref = dissipated(&v_ref[..n], &u_ref[..n], &a_ref[..n]);
    eprintln!(
        "{scene} ({name}): OpenSees {} iterations; base shear rms {rms:.3e}, max {:.3e} of peak {peak:.1} N; dissipated {w:.2} vs {w_ref:.2} J ({:.2e}); {} iterations, {} element iterations, {} subdivisions, {:.3} s",
        r["iterations"]["total"],
        worst / peak,
        (w - w_ref) / w_ref,
        run.iterations,
        run.element_iterations,
        run.subdivisions,
        run.seconds
    );
    assert!(rms < 0.01, "{scene}: rms {rms:e}");
    assert!(
        ((w - w_ref) / w_ref).abs() < 0.02,
        "{scene}: {w} vs {w_ref}"
    );
    run
}

// The c01 column (one force-based element, Concrete01 and Steel01) follows OpenSees' base
// shear over the whole protocol within 1 % RMS of the peak, and dissipates the same energy
// within 2 %.
#[test]
fn rc_cyclic_c01_matches_opensees() {
    let run = compare("rc_cyclic_c01", false, Newton::new(1e-20, 50).unwrap());
    assert!(run.failure.is_none());
    assert_eq!(run.shear.len(), protocol().len());
}

// On the c02 column (Concrete02 and Steel02) plain Newton stops with a typed failure at
// step 4154, the step where OpenSees' plain Newton also cycles (a core fiber flips between
// its loading and unloading branches on alternate iterations; the stored reference was made
// with OpenSees' KrylovNewton). Up to there the base shear follows the reference within 1 %
// RMS of the peak (measured: 8.8e-14). The agreement to round-off is fragile: with an
// earlier ordering of the same computations (each step re-assembling at its start), the run
// left OpenSees' path at step 1679 by 1e-4 of the peak. Near a fiber's load reversal the
// incremental problem has more than one converged solution, and round-off in Newton's
// iterates decides which one is found.
#[test]
fn rc_cyclic_c02_plain_newton_stops_where_opensees_does() {
    let run = compare("rc_cyclic_c02", true, Newton::new(1e-20, 50).unwrap());
    let (k, e) = run.failure.expect("plain Newton passes step 4154");
    assert_eq!(k, 4154);
    assert!(matches!(e, PathFailure::NoConvergence { .. }), "{e}");
}

// The energy line search (regula falsi on dx . r, the `_ls` variants) does not carry c02
// through the protocol either: it stops with a typed failure (measured: at step 4154 too;
// with the earlier ordering above, at step 1678), and up to there it follows the reference
// within 1 % RMS of the peak.
#[test]
fn rc_cyclic_c02_line_search_stops_with_a_typed_failure() {
    let run = compare(
        "rc_cyclic_c02",
        true,
        NewtonLineSearch::new(1e-20, 50).unwrap(),
    );
    let (k, e) = run.failure.expect("the line search completes c02");
    assert!(k < protocol().len());
    assert!(matches!(e, PathFailure::NoConvergence { .. }), "{e}");
}

// Krylov-accelerated Newton (the step's tangent reused, corrections accelerated over a
// subspace of at most 3, the algorithm the c02 reference was made with) carries the c02
// column through the whole protocol, including OpenSees' cycling step 4154, and follows the
// reference's base shear within 1 % RMS of the peak and its dissipated energy within 2 %.
#[test]
fn rc_cyclic_c02_krylov_passes_the_whole_protocol() {
    let run = compare("rc_cyclic_c02", true, KrylovNewton::new(1e-20, 50).unwrap());
    assert!(run.failure.is_none());
    assert_eq!(run.shear.len(), protocol().len());
}

// Krylov-accelerated Newton on the c01 column follows OpenSees' (plain Newton) base shear
// within 1 % RMS of the peak and its dissipated energy within 2 %, over the whole protocol.
#[test]
fn rc_cyclic_c01_krylov_matches_opensees() {
    let run = compare(
        "rc_cyclic_c01",
        false,
        KrylovNewton::new(1e-20, 50).unwrap(),
    );
    assert!(run.failure.is_none());
    assert_eq!(run.shear.len(), protocol().len());
}
