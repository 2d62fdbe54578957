//! Zero allocation per step: a counting global allocator (possible only in a separate test
//! binary) shows that, after construction, 1000 RKMK4 steps and 1000 accepted DOP853 steps
//! on a rigid body on SO(3) with springs and gravity perform no heap allocation at all (the
//! stage workspaces and error buffers live in the method structs; the springs are iterated
//! in place).
//!
//! The counter is thread-local, so allocations by the test harness's other threads do not
//! count.
use std::alloc::{GlobalAlloc, Layout, System as SysAlloc};
use std::cell::Cell;

use mbdbench::integrate::adaptive_rk::AdaptiveRk;
use mbdbench::integrate::explicit_rk::ExplicitRk;
use mbdbench::integrate::{Adaptive, FixedStep, Limits, Stats, System};
use mbdbench::math::so3;
use mbdbench::model::rigid_body::{Observation, RigidBody, RigidSystem, Spring};
use mbdbench::rotation::{Body, So3};
use nalgebra::{Matrix3, Vector3};

struct Counting;

thread_local! {
    static ALLOCS: Cell<u64> = const { Cell::new(0) };
}

fn bump() {
    let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
}

fn allocs() -> u64 {
    ALLOCS.with(|c| c.get())
}

// SAFETY: forwards every call unchanged to the system allocator; the counter is a
// const-initialised thread-local `Cell` (no allocation, no destructor).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        bump();
        unsafe { SysAlloc.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        bump();
        unsafe { SysAlloc.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { SysAlloc.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        bump();
        unsafe { SysAlloc.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn spring_body() -> RigidSystem<So3, Body> {
    let j = Matrix3::from_diagonal(&Vector3::new(0.4, 0.6, 0.8));
    let springs = vec![
        Spring {
            body_point: Vector3::new(0.5, 0.0, 0.0),
            anchor: Vector3::new(1.5, 0.0, 0.5),
            stiffness: 20.0,
            rest_length: 0.8,
        },
        Spring {
            body_point: Vector3::new(0.0, -0.3, 0.2),
            anchor: Vector3::new(-0.5, -1.2, 0.5),
            stiffness: 35.0,
            rest_length: 0.6,
        },
    ];
    RigidSystem::new(RigidBody::new(2.0, j, springs, Some(9.81), None).unwrap())
}

/// 1000 rk4 steps and 1000 accepted dop853 steps allocate nothing after construction.
#[test]
fn steps_do_not_allocate() {
    let sys = spring_body();
    let x0 = sys.state_from(&Observation {
        q: so3::exp_quat(&Vector3::new(0.2, 0.4, -0.1)),
        x: Vector3::new(0.1, -0.2, 0.3),
        v: Vector3::new(0.0, 0.3, 0.0),
        omega: Vector3::new(0.5, -1.0, 2.0),
    });
    let mut rk4 = ExplicitRk::rk4();
    let mut dop = AdaptiveRk::dop853(1e-9);
    let limits = Limits::default();

    // The counter sees this thread's allocations.
    let c0 = allocs();
    std::hint::black_box(vec![1u8; 16]);
    assert_eq!(allocs() - c0, 1);

    let before = allocs();
    let mut x = x0;
    let mut st = Stats::default();
    let h = 1e-3;
    for k in 0..1000 {
        let t = k as f64 * h;
        rk4.step(&sys, t, h, &mut x, &mut st).unwrap();
        sys.normalize(&mut x);
        sys.check(t + h, &x).unwrap();
    }
    let after_rk4 = allocs();

    let mut y = x0;
    let mut st2 = Stats::default();
    let mut k = 0;
    while st2.steps < 1000 {
        let (ta, tb) = (0.05 * k as f64, 0.05 * (k + 1) as f64);
        dop.advance(&sys, ta, tb, &mut y, &mut st2, &limits)
            .unwrap();
        k += 1;
    }
    let after_dop = allocs();

    assert_eq!(st.rhs_evals, 4000, "rk4: four evaluations a step");
    assert!(st2.steps >= 1000);
    assert_eq!(after_rk4 - before, 0, "rk4 allocated");
    assert_eq!(after_dop - after_rk4, 0, "dop853 allocated");
}

/// The whole run loop of a registered variant (`quat/rk4/body` on nine_spring, 1 s, outputs
/// every 0.1 s) allocates the same number of times for 1000 steps as for 10000: nothing is
/// allocated per step (only the setup and the reserved sample vector).
#[test]
fn registry_run_allocations_do_not_grow_with_steps() {
    let cases = mbdbench::catalogue::embedded().unwrap();
    let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
    let mut p =
        mbdbench::model::rigid_body::plan::scene_plan(c, c.scene("large").unwrap()).unwrap();
    p.setup.grid = mbdbench::run::Grid {
        t_end: 1.0,
        sample_every: 0.1,
        score_every: 0.1,
    };
    let v = mbdbench::model::rigid_body::registry::find("quat", "rk4", "body").unwrap();
    let _ = (v.run)(&p.setup, 1e-3).unwrap(); // warm up lazily initialised statics
    let count = |dt: f64| {
        let a0 = allocs();
        let out = (v.run)(&p.setup, dt).unwrap();
        let n = allocs() - a0;
        assert_eq!(out.stats.steps, (1.0 / dt).round() as u64);
        n
    };
    let coarse = count(1e-3);
    let fine = count(1e-4);
    assert_eq!(coarse, fine, "allocations grow with the number of steps");
    assert!(coarse < 20, "{coarse} allocations for one run");
}
