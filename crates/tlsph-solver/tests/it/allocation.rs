//! A step allocates nothing after warm-up: all per-step scratch lives in the simulation.
//!
//! A counting global allocator counts only on threads that opted in (this test's thread and the
//! workers of its own rayon pool, until they exit), so tests running concurrently in this
//! binary do not disturb the count; the measuring tests take one lock, so two of them never count at the same time
//! into the shared counter.

use super::{lattice, model, Setup};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use tlsph_math::Vector;
use tlsph_solver::{BoundaryDescription, Formulation, Model, Simulation, StressUpdate};

struct CountingAllocator;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

/// Held while a test counts: the counter is shared by every opted-in thread.
static MEASURING: Mutex<()> = Mutex::new(());

thread_local! {
    // Const-initialised and without destructor, so reading it never allocates.
    static COUNTED: Cell<bool> = const { Cell::new(false) };
}

fn count() {
    if COUNTED.with(Cell::get) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: forwards every call unchanged to the system allocator; only adds a counter.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc(layout)
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc_zeroed(layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        System.realloc(ptr, layout, new_size)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// Allocations counted on this thread and the pool's workers while `steps` steps run, after
/// two warm-up steps.
fn allocations_during_steps<const D: usize>(model: Model<D>, steps: usize) -> usize {
    let _measuring = MEASURING.lock().unwrap_or_else(|e| e.into_inner());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .start_handler(|_| COUNTED.with(|c| c.set(true)))
        // A worker's thread-local destructors (crossbeam's epoch handle) allocate when it
        // exits, which happens after this pool is dropped, possibly while a later test counts:
        // a worker stops counting before it exits.
        .exit_handler(|_| COUNTED.with(|c| c.set(false)))
        .build()
        .unwrap();
    let mut sim = Simulation::new(model).unwrap();
    pool.install(|| {
        sim.step().unwrap();
        sim.step().unwrap();
    });
    // Every worker takes a job from its own broadcast queue, so each has set up its
    // work-stealing state (crossbeam's epoch handle, allocated on a thread's first steal): on
    // a loaded machine one worker may have taken no part in the warm-up steps and would set
    // it up, once, in the first measured step.
    pool.broadcast(|_| ());
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    COUNTED.with(|c| c.set(true));
    pool.install(|| {
        for _ in 0..steps {
            sim.step().unwrap();
        }
    });
    COUNTED.with(|c| c.set(false));
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

#[test]
fn the_counting_allocator_counts_on_opted_in_threads() {
    let _measuring = MEASURING.lock().unwrap_or_else(|e| e.into_inner());
    COUNTED.with(|c| c.set(true));
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let v = std::hint::black_box(vec![1.0f64; 16]);
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    COUNTED.with(|c| c.set(false));
    drop(v);
    assert!(after > before);
}

#[test]
fn a_step_does_not_allocate_after_warm_up() {
    let dx = 0.02;
    // Large enough that rayon splits every loop across both workers.
    for (formulation, stress_update) in [
        (Formulation::TotalLagrangian, StressUpdate::JaumannRate),
        (
            Formulation::TotalLagrangianCorrected,
            StressUpdate::GreenLagrange,
        ),
        // Between Verlet-list rebuilds (the slow motion here moves no particle by half the
        // skin in five steps), the updated-Lagrangian step allocates nothing either.
        (Formulation::UpdatedLagrangian, StressUpdate::JaumannRate),
    ] {
        let setup = || Setup {
            formulation,
            stress_update,
            ..Setup::default()
        };
        let v2 = |x: &Vector<2>| Vector::<2>::new(0.05 * x[1], -0.02 * x[0]);
        let mut m2 = model(lattice([40, 30], dx), dx, v2, setup());
        m2.boundaries.push(BoundaryDescription {
            name: "clamp".into(),
            body: 0,
            particles: (0..30).collect(),
            velocity: Vector::<2>::zeros(),
            components: [true, true],
            amplitude: None,
        });
        let n = allocations_during_steps(m2, 5);
        assert_eq!(
            n, 0,
            "{formulation:?}/{stress_update:?} 2D: {n} allocations"
        );
        let v3 = |x: &Vector<3>| Vector::<3>::new(0.05 * x[1], 0.0, 0.01 * x[0]);
        let m3 = model(lattice([12, 10, 8], dx), dx, v3, setup());
        let n = allocations_during_steps(m3, 5);
        assert_eq!(
            n, 0,
            "{formulation:?}/{stress_update:?} 3D: {n} allocations"
        );
    }
}

#[test]
fn a_contact_step_does_not_allocate_between_candidate_list_rebuilds() {
    // Two blocks pressed together slowly: the contact is active (forces, energy, time-step
    // vote every step) but nobody moves half the skin within the counted steps.
    let dx = 0.02;
    let mut m = model(
        lattice([30, 20], dx),
        dx,
        |_| Vector::<2>::new(0.0, -0.01),
        Setup::default(),
    );
    let mut top = m.bodies[0].clone();
    top.name = "top".into();
    top.positions = lattice([30, 20], dx)
        .iter()
        .map(|x| x + Vector::<2>::new(0.0, 20.0 * dx - 0.001 * dx))
        .collect();
    top.velocities = vec![Vector::<2>::new(0.0, -0.01); top.positions.len()];
    m.bodies[0].velocities.fill(Vector::<2>::new(0.0, 0.01));
    m.bodies.push(top);
    m.effects.contact = Some(tlsph_solver::ContactDescription {
        scale: 0.5,
        exponent: 4.0,
        pairs: None,
    });
    let mut sim = Simulation::new(m.clone()).unwrap();
    for _ in 0..7 {
        sim.step().unwrap();
    }
    assert_eq!(
        sim.contact_rebuilds(),
        Some(1),
        "no rebuild after the first in 7 steps"
    );
    let d = sim.diagnostics();
    assert!(d.effect_energies[0].1 > 0.0, "contact is active: {d:?}");
    let n = allocations_during_steps(m, 5);
    assert_eq!(n, 0, "{n} allocations");
}
