//! A step allocates nothing: counted by a global allocator wrapped around the system one.

use rope::method::MethodKind;
use rope::scene::Scene;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn steps_of_every_method_allocate_nothing() {
    for kind in MethodKind::ALL {
        let scene = Scene::Release { angle_deg: 30.0 };
        let mut method = kind.build(&scene, 200, kind.default_dt(200)).unwrap();
        method.step().unwrap(); // warm up
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        for _ in 0..500 {
            method.step().unwrap();
        }
        let energy = method.energy();
        let after = ALLOCATIONS.load(Ordering::SeqCst);
        assert_eq!(
            after - before,
            0,
            "{kind}: {} allocations in 500 steps",
            after - before
        );
        assert!(energy.total().is_finite());
    }
}
