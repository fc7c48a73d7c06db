//! A long-lived process (a Python session, a server) solves many models read at run time:
//! nothing of a model may outlive its solve. Measured with a counting allocator, so this is
//! its own test binary (the allocator is global to the binary it is in).

use model_interpreted::{solve, ModelFile, SolveRequest};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicIsize, Ordering};

/// The system allocator, counting the bytes held.
struct Counting;

static HELD: AtomicIsize = AtomicIsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        HELD.fetch_add(layout.size() as isize, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        HELD.fetch_sub(layout.size() as isize, Ordering::Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        HELD.fetch_add(
            new_size as isize - layout.size() as isize,
            Ordering::Relaxed,
        );
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// A smooth model that solves, one whose pivot is zero at the start (its error names the
/// pivot and the model), and a switched one with events: each read, compiled and solved.
fn read_and_solve_three_models(round: usize) {
    // A different name each round (of one length: buffers that keep the longest name seen
    // are not leaks): names are what a leak would keep.
    let smooth = format!(
        "mod oscillator_{round:04} {{ params {{ w = 3 }} states {{ x, v }}
         equations {{ der(x) = v; der(v) = -w^2 * x; }} outputs {{ speed = v; }} }}"
    );
    let singular =
        format!("mod singular_{round:04} {{ states {{ x }} equations {{ x * der(x) = 1; }} }}");
    let switched =
        include_str!("held_ball.dsl").replace("mod ball", &format!("mod ball_{round:04}"));
    for (text, solves) in [(smooth, true), (singular, false), (switched, true)] {
        let file = ModelFile::from_text("model.dsl", &text).expect("the model compiles");
        let model = file.model(None).expect("one model");
        let outcome = solve(model, &SolveRequest::new(1.0));
        assert_eq!(outcome.is_ok(), solves, "{text}: {:?}", outcome.err());
        if let Err(failure) = outcome {
            assert!(
                failure
                    .to_string()
                    .contains(&format!("singular_{round:04}")),
                "{failure}"
            );
        }
    }
}

#[test]
fn solving_many_models_keeps_nothing_of_them() {
    // The first rounds may fill caches that live for the process (thread-locals, the
    // formatter's buffers); after them every round must give back what it took.
    for round in 0..3 {
        read_and_solve_three_models(round);
    }
    let before = HELD.load(Ordering::Relaxed);
    for round in 3..53 {
        read_and_solve_three_models(round);
    }
    let kept = HELD.load(Ordering::Relaxed) - before;
    // Leaking the names alone would keep several hundred bytes per model.
    assert!(kept <= 0, "50 rounds of three models kept {kept} bytes");
}
