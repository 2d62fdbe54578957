//! Zero allocation per step of the implicit Gauss methods: a counting global allocator
//! records the allocations made by this test's thread while `gauss6` (and
//! `implicit_midpoint`) take 200 RKMK steps on `RigidSystem<So3, Body>` with a spring right
//! after construction (the first step, with its Jacobian and factorization, included); the
//! count must be 0. Only the current thread is counted, so the test harness's own threads do not
//! interfere.
use std::alloc::{GlobalAlloc, Layout, System as SysAlloc};
use std::cell::Cell;

use mbdbench::integrate::implicit_rk::ImplicitRk;
use mbdbench::integrate::{FixedStep, Stats, System};
use mbdbench::model::rigid_body::{Observation, RigidBody, RigidSystem, Spring};
use mbdbench::rotation::{Body, So3};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

struct Counting;

thread_local! {
    static ON: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<u64> = const { Cell::new(0) };
}

fn note() {
    // `try_with`: the thread-locals may be gone during thread teardown.
    let _ = ON.try_with(|on| {
        if on.get() {
            let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        }
    });
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { SysAlloc.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { SysAlloc.dealloc(ptr, layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { SysAlloc.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        unsafe { SysAlloc.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations_in(f: impl FnOnce()) -> u64 {
    COUNT.with(|c| c.set(0));
    ON.with(|on| on.set(true));
    f();
    ON.with(|on| on.set(false));
    COUNT.with(|c| c.get())
}

/// 200 steps of gauss6 and of implicit_midpoint allocate nothing.
#[test]
fn implicit_steps_do_not_allocate() {
    let body = RigidBody::new(
        2.0,
        Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)),
        vec![Spring {
            body_point: Vector3::new(0.3, 0.2, 0.1),
            anchor: Vector3::new(0.5, -0.2, 1.0),
            stiffness: 20.0,
            rest_length: 0.5,
        }],
        None,
        None,
    )
    .unwrap();
    let sys: RigidSystem<So3, Body> = RigidSystem::new(body);
    let x0 = sys.state_from(&Observation {
        q: UnitQuaternion::from_euler_angles(0.3, -0.2, 0.5),
        x: Vector3::new(0.1, 0.0, 0.2),
        v: Vector3::new(0.2, -0.1, 0.3),
        omega: Vector3::new(2.0, 1.0, -0.6),
    });
    // A sanity check of the counter itself.
    assert!(allocations_in(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    for mut method in [
        ImplicitRk::<RigidSystem<So3, Body>>::gauss6(),
        ImplicitRk::<RigidSystem<So3, Body>>::implicit_midpoint(),
    ] {
        let (h, mut x, mut stats) = (0.01, x0, Stats::default());
        let mut ok = true;
        let n = allocations_in(|| {
            for k in 0..200 {
                let t = k as f64 * h;
                ok &= method.step(&sys, t, h, &mut x, &mut stats).is_ok();
                stats.steps += 1; // the run loop counts steps
                sys.normalize(&mut x);
                ok &= sys.check(t + h, &x).is_ok();
            }
        });
        assert!(ok, "all 200 steps succeed");
        assert_eq!(stats.steps, 200);
        assert_eq!(n, 0, "{}: {n} allocations in 200 steps", method.info().name);
        eprintln!(
            "{}: 0 allocations; per step {:.2} Newton iterations, {:.2} rhs evaluations, \
             {} Jacobians",
            method.info().name,
            stats.newton_iters as f64 / 200.0,
            stats.rhs_evals as f64 / 200.0,
            method.jacobian_evals()
        );
    }
}
