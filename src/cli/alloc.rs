//! The binary's global allocator: mimalloc, counting live heap bytes so that
//! `vesselcad bench` and `vesselcad info --memory` report measured memory rather
//! than estimates.
//!
//! mimalloc because glibc's allocator did not scale: a 2 000-vessel plant built
//! 1.60× faster on 2 threads than on 1 with it and 1.94× with mimalloc (same run
//! order, same machine), the meshing stage being allocation-heavy on every
//! thread. Each thread adds its allocations to a thread-local balance and moves
//! it to the shared total once it passes [`FLUSH`] bytes either way, so the
//! threads do not fight over one counter's cache line on every allocation.
//!
//! The batch commands also keep freed memory rather than hand it back to the
//! system ([`vesselcad::allocator::hold_freed_memory`]). mimalloc returns pages unused for a second
//! (`madvise`), and a build that frees and reallocates gigabytes of meshing
//! scratch then faults them in again: about 720 000 minor faults and 30 s of
//! kernel time in `vesselcad bench` at 10 000 vessels. With purging off that is
//! 4 500 faults, and the 2-thread build ran at 320–344 vessels/s against
//! 293–307 with it (1.87–2.03× over 1 thread against 1.65–1.87×; three runs each,
//! alternating, on this 2-core VM). The price is a higher peak (8.0 GB against
//! 7.2 GB there), which a command that exits anyway can pay; `serve` keeps
//! mimalloc's default, so a long session gives memory back.

use std::alloc::{GlobalAlloc, Layout};
use std::cell::Cell;

use mimalloc::MiMalloc;
use std::sync::atomic::{AtomicIsize, Ordering};

/// mimalloc, counting live bytes.
pub struct Counting;

static LIVE: AtomicIsize = AtomicIsize::new(0);

/// Bytes a thread's balance may hold before it moves to [`LIVE`]: the total is
/// exact to within this much per thread.
const FLUSH: isize = 256 * 1024;

thread_local! {
    /// This thread's allocations not yet added to [`LIVE`] (const-initialised,
    /// no destructor: safe to touch from inside the allocator).
    static BALANCE: Cell<isize> = const { Cell::new(0) };
}

/// Adds `bytes` (negative for a free) to this thread's balance, moving the
/// balance to the shared total when it grows past [`FLUSH`].
fn count(bytes: isize) {
    let moved = BALANCE
        .try_with(|b| {
            let v = b.get() + bytes;
            if v.abs() >= FLUSH {
                b.set(0);
                v
            } else {
                b.set(v);
                0
            }
        })
        // A thread being torn down has no balance left: count directly.
        .unwrap_or(bytes);
    if moved != 0 {
        LIVE.fetch_add(moved, Ordering::Relaxed);
    }
}

// SAFETY: every call forwards to `MiMalloc` with the caller's arguments unchanged;
// the counter is bookkeeping only.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded as is.
        let p = unsafe { MiMalloc.alloc(layout) };
        if !p.is_null() {
            count(layout.size() as isize);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded as is.
        unsafe { MiMalloc.dealloc(ptr, layout) };
        count(-(layout.size() as isize));
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded as is.
        let p = unsafe { MiMalloc.alloc_zeroed(layout) };
        if !p.is_null() {
            count(layout.size() as isize);
        }
        p
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: forwarded as is.
        let p = unsafe { MiMalloc.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            count(new_size as isize - layout.size() as isize);
        }
        p
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Heap bytes allocated and not yet freed: exact to within [`FLUSH`] bytes per
/// thread that has allocated (the balances not yet moved to the total).
pub fn live_bytes() -> usize {
    LIVE.load(Ordering::Relaxed).max(0) as usize
}
