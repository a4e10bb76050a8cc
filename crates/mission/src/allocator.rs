//! The allocator setting a process flying many missions needs: one definition for the
//! `karman` binary and the Python package.

/// Keeps freed heap memory in the process instead of returning it to the kernel at every
/// free; call it once, at start-up, before any other thread exists.
///
/// glibc gives the top of its heap back (`brk`/`madvise`) whenever more than 128 KiB lie free
/// there. Each Monte Carlo sample (and each `simulate()` of the Python package) builds and
/// drops about half a megabyte of tables and trajectory, so with the default every flight
/// shrinks the heap and page-faults it back in: about a tenth of a Monte Carlo run's time
/// went to the kernel (docs/performance.md). A 4 MiB threshold keeps the memory of one
/// flight per thread in reserve; the peak resident size is unchanged. Other allocators
/// decide for themselves (a no-op there).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
pub fn keep_freed_heap() {
    const TRIM_THRESHOLD: libc::c_int = 4 << 20;
    // SAFETY: `mallopt` only sets an allocator parameter (glibc serialises it with its own
    // lock); it takes no pointers.
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
    }
}

/// Other allocators decide for themselves.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub fn keep_freed_heap() {}
