//! A step allocates nothing, and refusing an impossible run allocates nothing of its size:
//! counted by a global allocator wrapped around the system one, counting only on the thread
//! that measures (the test harness allocates on its own).

use rope::methods::MethodKind;
use rope::model::Scene;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Set while this thread measures. Both cells are per thread (tests run in parallel) and
    /// const-initialised, so touching them never allocates.
    static MEASURING: Cell<bool> = const { Cell::new(false) };
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if MEASURING.try_with(Cell::get).unwrap_or(false) {
            let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
            let _ = LARGEST.try_with(|n| n.set(n.get().max(layout.size())));
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made on this thread while `work` runs.
fn allocations_in(work: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    MEASURING.with(|m| m.set(true));
    work();
    MEASURING.with(|m| m.set(false));
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn the_counter_sees_an_allocation() {
    let n = allocations_in(|| {
        std::hint::black_box(vec![1u8; 64]);
    });
    assert_eq!(n, 1);
}

#[test]
fn steps_of_every_method_allocate_nothing() {
    for kind in MethodKind::ALL {
        let scene = Scene::Release { angle_deg: 30.0 };
        let mut method = kind.build(&scene, 200, kind.default_dt(200)).unwrap();
        method.step().unwrap(); // warm up
        let mut energy = 0.0;
        let n = allocations_in(|| {
            for _ in 0..500 {
                method.step().unwrap();
            }
            energy = method.energy().total();
        });
        assert_eq!(n, 0, "{kind}: {n} allocations in 500 steps");
        assert!(energy.is_finite());
    }
}

/// The largest single allocation made on this thread while `work` runs, in bytes.
fn largest_allocation_in(work: impl FnOnce()) -> usize {
    LARGEST.with(|n| n.set(0));
    allocations_in(work);
    LARGEST.with(Cell::get)
}

#[test]
fn refusing_runs_too_large_for_the_machine_allocates_nothing_of_their_size() {
    use clap::Parser as _;
    use rope::cli::{Cli, Command};
    for flags in [
        &["--segments", "100000000"][..],
        &["--segments", "18446744073709551615"][..],
        &["--tolerance", "1e-12"][..],
        &["--duration", "1e300"][..],
    ] {
        let mut args = vec!["rope", "run"];
        args.extend_from_slice(flags);
        let Command::Run(run) = Cli::try_parse_from(&args).unwrap().command else {
            unreachable!("a run");
        };
        let mut refused = None;
        let largest = largest_allocation_in(|| refused = Some(run.plans().is_err()));
        assert_eq!(refused, Some(true), "{flags:?} must be refused");
        assert!(
            largest < 1 << 20,
            "{flags:?}: allocated {largest} bytes at once"
        );
    }
}
