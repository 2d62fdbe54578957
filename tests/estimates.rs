//! The families' memory estimates (`problem::Family::estimate`, cases/README.md "Budgets")
//! against the heap they describe, measured by a counting global allocator (possible only in
//! a separate test binary): loading a case whose numbers ask for gigabytes refuses it, naming
//! the key, while the loader itself holds a few megabytes at most (the estimate comes before
//! anything that grows with the numbers); and a run's peak heap lies within its scene's
//! estimate, which overstates it by a small factor at most (an honest estimate, not a bound
//! pulled from the air).
//!
//! The counters are thread-local (the loads and runs here happen on the test's thread), so
//! allocations by the harness's other threads do not count.
use std::alloc::{GlobalAlloc, Layout, System as SysAlloc};
use std::cell::Cell;

use mbdbench::case::{self, Case};
use mbdbench::problem::{Stepping, Want};

struct Counting;

thread_local! {
    static NOW: Cell<i64> = const { Cell::new(0) };
    static PEAK: Cell<i64> = const { Cell::new(0) };
}

fn add(n: i64) {
    let _ = NOW.try_with(|c| {
        let v = c.get() + n;
        c.set(v);
        let _ = PEAK.try_with(|p| p.set(p.get().max(v)));
    });
}

// SAFETY: forwards every call unchanged to the system allocator; the counters are
// const-initialised thread-local `Cell`s (no allocation, no destructor).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        add(layout.size() as i64);
        unsafe { SysAlloc.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        add(layout.size() as i64);
        unsafe { SysAlloc.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        add(-(layout.size() as i64));
        unsafe { SysAlloc.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        add(new_size as i64 - layout.size() as i64);
        unsafe { SysAlloc.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// `f`'s result and the most heap (bytes) it held at once above what was held before it.
fn peak_of<R>(f: impl FnOnce() -> R) -> (R, u64) {
    let base = NOW.with(|c| c.get());
    PEAK.with(|p| p.set(base));
    let r = f();
    (r, (PEAK.with(|p| p.get()) - base).max(0) as u64)
}

/// The catalogue file `name` with each `(old, new)` replaced once (each must occur).
fn edited(name: &str, edits: &[(&str, &str)]) -> (String, String) {
    let label = format!("cases/{name}.toml");
    let (_, text) = case::embedded_sources()
        .iter()
        .find(|(l, _)| *l == label)
        .expect("a catalogue file");
    let mut t = text.to_string();
    for (old, new) in edits {
        assert!(t.contains(old), "{name} no longer contains `{old}`");
        t = t.replacen(old, new, 1);
    }
    (label, t)
}

fn load(name: &str, edits: &[(&str, &str)]) -> Case {
    let (label, text) = edited(name, edits);
    mbdbench::catalogue::load_str(&label, &text).unwrap_or_else(|e| panic!("{e}"))
}

/// Case files whose numbers ask for gigabytes (a 384 GB protocol, 1e10 fibers, 1e12
/// elements) are refused while loading, naming the key, and the loader holds under 4 MB of
/// heap doing it.
#[test]
fn hostile_numbers_are_refused_before_anything_large_exists() {
    let drifts = "drifts = [0.0025, 0.005, 0.01, 0.015, 0.02, 0.03, 0.04]";
    let cases: [(&str, &str, &str, &str); 8] = [
        (
            "fiber_column_cyclic",
            drifts,
            "drifts = [1.0e6]",
            "scene[0].t_end",
        ),
        (
            "fiber_column_cyclic",
            "cycles = 2,",
            "cycles = 1.0e6,",
            "scene[0].t_end",
        ),
        (
            "fiber_column_cyclic",
            "increment = 5.0e-4",
            "increment = 1.0e-12",
            "scene[0].t_end",
        ),
        (
            "fiber_column_cyclic",
            "ny = 16, nz = 2 }",
            "ny = 100000, nz = 100000 }",
            "section.patches[0].ny",
        ),
        (
            "fiber_column_cyclic",
            "n = 4, area",
            "n = 1.0e12, area",
            "section.layers[0].n",
        ),
        (
            "fiber_column_cyclic",
            "elements = 1\n",
            "elements = 1.0e12\n",
            "numerics.elements",
        ),
        (
            "fiber_column_static",
            "elements = 10\n",
            "elements = 10000\n",
            "numerics.elements",
        ),
        (
            "flexible_beam",
            "elements = 10\n",
            "elements = 1.0e9\n",
            "numerics.elements",
        ),
    ];
    for (name, old, new, key) in cases {
        let (label, text) = edited(name, &[(old, new)]);
        let (r, peak) = peak_of(|| mbdbench::catalogue::load_str(&label, &text));
        let e = r.expect_err(new);
        assert_eq!(e.file, label);
        assert_eq!(e.key, key, "{new}: {e}");
        assert!(peak < 4 << 20, "{new}: the loader held {peak} bytes");
    }
}

/// One run of `case`'s scene `scene` (the variant and step given, over the first `t_end`):
/// its peak heap lies within the scene's estimate, which is at most `slack` times it.
fn run_within(c: &Case, scene: &str, variant: (&str, &str, &str), dt: f64, t_end: f64, slack: f64) {
    let s = c.scene(scene).expect("a scene");
    let family = mbdbench::catalogue::family_of(c);
    let e = (family.estimate)(c, s);
    let v = family
        .find(variant.0, variant.1, variant.2)
        .expect("a registered variant");
    let mut p = (family.compile)(c, s).unwrap();
    if t_end < s.t_end {
        p.set_t_end(t_end);
    }
    let (out, peak) = peak_of(|| p.run(v, Stepping::Dt(dt), Want::Trajectory).unwrap());
    assert!(out.failure.is_none(), "{scene}: {:?}", out.failure);
    assert!(
        peak <= e.bytes,
        "{}/{scene}: the run held {peak} bytes, the estimate says {}",
        c.name,
        e.bytes
    );
    assert!(
        e.bytes as f64 <= slack * peak as f64,
        "{}/{scene}: the estimate {} overstates the run's {peak} bytes",
        c.name,
        e.bytes
    );
}

/// The fiber column's estimate holds the dense tangent of a 200-element mesh (1,200
/// unknowns, 23 MB) and the sections of a displacement-based mesh of 8 x 5 sections of
/// 9,722 fibers (its work budget raised to the cap), within a factor 2 of what the runs
/// hold.
#[test]
fn fiber_column_estimates_hold_their_runs() {
    let c = load(
        "fiber_column_static",
        &[("elements = 10\n", "elements = 200\n")],
    );
    let fb = ("so3", "newton_load", "force_based");
    run_within(&c, "elastica_p1", fb, 0.1, 1.0, 2.0);
    let c = load(
        "fiber_column_cyclic",
        &[
            ("ny = 16, nz = 2 }", "ny = 160, nz = 60 }"),
            (
                "reference = \"external\"\n",
                "reference = \"external\"\nmax_work = 3.6e12\n",
            ),
        ],
    );
    let db = ("so3", "newton_disp", "disp_based_n8");
    run_within(&c, "rc_cyclic_c01", db, 5.0, 15.0, 2.0);
}

/// The flexible beam's estimate holds `fe_exact`'s three dense matrices of 60 elements (its
/// work budget raised to the cap: the reference's self-convergence track of that mesh would
/// take many minutes) and the rigid body's its samples, within a factor 3 of what the runs
/// hold.
#[test]
fn beam_and_rigid_body_estimates_hold_their_runs() {
    let c = load(
        "flexible_beam",
        &[
            ("elements = 10\n", "elements = 60\n"),
            ("reference_elements = 40\n", "reference_elements = 60\n"),
            (
                "reference = \"numerical\"\n",
                "reference = \"numerical\"\nmax_work = 3.6e12\n",
            ),
        ],
    );
    run_within(
        &c,
        "spinup_w4",
        ("none", "newmark", "fe_exact"),
        5.0e-2,
        1.0,
        3.0,
    );
    let two_angles = "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 10.0\nsample_every = 0.01";
    let c = load(
        "nine_spring",
        &[(two_angles, &two_angles.replace("0.01", "1.0e-4"))],
    );
    run_within(&c, "two_angles", ("so3", "rk4", "body"), 1.0e-4, 10.0, 3.0);
}
