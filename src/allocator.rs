//! Tuning of mimalloc, the binary's allocator (`src/cli/alloc.rs`): whether
//! freed memory goes back to the system. Sits outside the data flow; called once
//! by a command before its work, and by the profiling examples so that they
//! measure what the binary runs. In the library so both reach one definition;
//! harmless where mimalloc is linked but not the global allocator (its options
//! are its own).
//!
//! mimalloc v3 returns memory unused for a second to the system (`madvise`). A
//! plant build frees and reallocates gigabytes of meshing scratch, so it faulted
//! them in again and again: about 720 000 minor faults in `vesselcad bench` at
//! 10 000 vessels, which cost the 2-thread build most (see `cli::alloc`).

use libmimalloc_sys::{mi_option_set, mi_option_t};

/// mimalloc's `mi_option_purge_delay` (`include/mimalloc.h`, v3): how many
/// milliseconds freed memory waits before it is returned to the system; -1 for
/// never. `libmimalloc-sys` does not name it.
const PURGE_DELAY: mi_option_t = 15;

/// Keeps freed memory in the process for reuse instead of returning it to the
/// system after a delay (see the module doc). For commands that run to
/// completion; call before the heavy work starts.
pub fn hold_freed_memory() {
    // SAFETY: plain option setter of the linked mimalloc; any value is valid.
    unsafe { mi_option_set(PURGE_DELAY, -1) };
}

/// mimalloc's current purge delay, ms (-1: never).
#[cfg(test)]
fn purge_delay() -> std::ffi::c_long {
    // SAFETY: plain option getter of the linked mimalloc.
    unsafe { libmimalloc_sys::mi_option_get(PURGE_DELAY) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hold_freed_memory_turns_purging_off() {
        // Option 15 is the purge delay: it starts at mimalloc v3's default of
        // 1000 ms (unless the environment set it), and holding sets it to never.
        if std::env::var_os("MIMALLOC_PURGE_DELAY").is_none() {
            assert_eq!(purge_delay(), 1000);
        }
        hold_freed_memory();
        assert_eq!(purge_delay(), -1);
    }
}
