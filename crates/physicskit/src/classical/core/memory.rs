//! Trajectory storage: refusing what would not fit in memory before allocating it, and
//! allocating the rest so that filling it is cheap.

use std::sync::OnceLock;

use super::error::{Error, Result};

/// See [`set_memory_release_hook`].
static RELEASE_HOOK: OnceLock<fn()> = OnceLock::new();

/// Registers `release`, to be called when a trajectory would not fit in the available memory,
/// before the run is refused; the check is then made once more.
///
/// The check reads what the OS reports as available. An allocator that keeps freed memory
/// for reuse (the Python extension's mimalloc keeps it for a second, so that repeated runs do
/// not fault their storage in again) holds memory the OS counts as used although the next
/// trajectory could take it: the hook hands it back (`mi_collect(true)`) so that such a run
/// is not refused. Returns `false`, leaving the first hook in place, if one was registered
/// already.
pub fn set_memory_release_hook(release: fn()) -> bool {
    RELEASE_HOOK.set(release).is_ok()
}

/// Fraction of the available memory one result may take: the rest is left to the OS, the
/// caller and (from Python) numpy's copies.
const MAX_FRACTION_OF_AVAILABLE: f64 = 0.8;

/// Bytes of memory available to this process, if the platform tells.
fn available_bytes() -> Option<u128> {
    // Linux reports what can be allocated without swapping in /proc/meminfo.
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// The most one result may take: [`MAX_FRACTION_OF_AVAILABLE`] of what is available.
/// Without a reading, the address space is the limit (allocation is then also checked with
/// `try_reserve`).
fn budget_bytes() -> u128 {
    let available = available_bytes().unwrap_or(isize::MAX as u128);
    (available as f64 * MAX_FRACTION_OF_AVAILABLE) as u128
}

/// Trajectories up to this size are accepted by [`check_fits`] without reading the available
/// memory (on Linux a read of `/proc/meminfo`, which costs more than a short run: the lab
/// integrates a frame of a few steps sixty times a second). Refusing one would take less than
/// 1.25 MiB available (the budget is 80% of it), a machine too short of memory to have started
/// this process; so no trajectory that was accepted before is refused now, and one refused only
/// under such starvation is now left to the allocator, which reports failure as an error
/// (`storage` uses `try_reserve`).
const TRAJECTORY_ALWAYS_FITS_BYTES: u128 = 1 << 20;

/// Checks that `samples * values_per_sample` f64 values fit in memory.
///
/// # Errors
/// [`Error::TrajectoryTooLarge`].
pub(crate) fn check_fits(samples: usize, values_per_sample: usize) -> Result<()> {
    let bytes = samples as u128 * values_per_sample as u128 * 8;
    if bytes <= TRAJECTORY_ALWAYS_FITS_BYTES {
        return Ok(());
    }
    let budget = budget_after_release(bytes);
    if bytes > budget {
        return Err(Error::TrajectoryTooLarge {
            samples: samples as u128,
            values_per_sample,
            bytes,
            available: budget,
        });
    }
    Ok(())
}

/// Blocks up to this size are never refused by [`check_items_fit`]: they are small next to
/// any machine's memory, and constructors of small systems (the usual case, often in loops)
/// then do not read `/proc/meminfo`.
const ALWAYS_FITS_BYTES: u128 = 16 << 20;

/// Checks, before anything is allocated, that `n` items of `item_bytes` bytes each fit in
/// memory, by the budget `check_fits` applies to trajectories (the same fraction of the
/// available memory, after the same release hook).
///
/// For constructors whose allocations a user's size parameter `name` (a chain's `n`, a
/// swarm's `n`, a Lagrangian's `ndof`) controls: `item_bytes` is everything the call
/// allocates per unit of the parameter (for an `n x n` matrix, a row: `8 n`). The product is
/// formed in `u128`, so no `usize` input can overflow it (`n = 2^62` is refused, not wrapped).
/// Blocks up to 16 MiB are accepted without reading the available memory.
///
/// # Example
/// ```
/// use physicskit::classical::core::check_items_fit;
///
/// assert!(check_items_fit("n", 1000, 64).is_ok());
/// assert!(check_items_fit("n", 1 << 62, 64).is_err()); // 2^68 bytes
/// ```
///
/// # Errors
/// [`Error::TooLarge`] naming `name`.
pub fn check_items_fit(name: &str, n: usize, item_bytes: usize) -> Result<()> {
    // Two factors below 2^64 multiply to below 2^128: the product cannot overflow.
    let bytes = n as u128 * item_bytes as u128;
    if bytes <= ALWAYS_FITS_BYTES {
        return Ok(());
    }
    let budget = budget_after_release(bytes);
    if bytes > budget {
        return Err(Error::TooLarge {
            name: name.to_string(),
            value: n as u128,
            item_bytes: item_bytes as u128,
            bytes,
            available: budget,
        });
    }
    Ok(())
}

/// The budget, read again after calling the release hook if `bytes` exceeds it.
fn budget_after_release(bytes: u128) -> u128 {
    let budget = budget_bytes();
    if bytes <= budget {
        return budget;
    }
    match RELEASE_HOOK.get() {
        Some(release) => {
            release();
            budget_bytes()
        }
        None => budget,
    }
}

/// Smallest allocation worth faulting in up front, in one call: below it, the block is a few
/// pages of the heap, most likely present already.
const PREFAULT_MIN_BYTES: usize = 64 << 10;

/// An empty vector with room for `len` values, for storage filled once, front to back.
///
/// Nothing is written up front: neither `vec![0.0; len]` (`calloc` zeroes blocks it reuses
/// from the heap: on a repeated 2-dof run that `memset` cost as much as the steps) nor an
/// explicit fill. Filling fresh memory still costs a page fault per 4 KiB page, which on this
/// (virtualized) machine was a large part of what a system spends per stored sample, so blocks
/// from 64 KiB are faulted in at once, in one system call (`madvise(MADV_POPULATE_WRITE)`,
/// Linux 5.14; a hint, ignored where unsupported).
///
/// Transparent huge pages (`MADV_HUGEPAGE`) were tried for large blocks and dropped: faster at
/// best, but several times slower in most runs, when the kernel compacted memory to find huge
/// pages (`defrag = madvise` here). Measurements: `benchmarks/README.md`.
///
/// # Errors
/// [`Error::TrajectoryTooLarge`] if the allocator refuses the block.
pub(crate) fn storage(len: usize) -> Result<Vec<f64>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| Error::TrajectoryTooLarge {
            samples: len as u128,
            values_per_sample: 1,
            bytes: len as u128 * 8,
            available: 0,
        })?;
    let spare = v.spare_capacity_mut();
    let bytes = std::mem::size_of_val(spare);
    if bytes >= PREFAULT_MIN_BYTES {
        prefault(spare.as_ptr() as usize, bytes);
    }
    Ok(v)
}

/// Faults the pages of `[start, start + bytes)` in now, in one system call, rather than one
/// trap per page while the loop fills them.
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn prefault(start: usize, bytes: usize) {
    /// `MADV_POPULATE_WRITE` (Linux 5.14, `include/uapi/asm-generic/mman-common.h`); not
    /// exported by every `libc` target module.
    const MADV_POPULATE_WRITE: libc::c_int = 23;
    // SAFETY: `sysconf` reads a constant of the running kernel and touches no memory of ours.
    let page = match unsafe { libc::sysconf(libc::_SC_PAGESIZE) } {
        p if p > 0 => p as usize,
        _ => return,
    };
    let end = start + bytes;
    let first = start.next_multiple_of(page);
    if end <= first {
        return;
    }
    let len = (end - first) / page * page;
    // SAFETY: the range [first, first + len) lies inside the caller's allocation.
    // MADV_POPULATE_WRITE faults its pages in as a write would, without writing: what the
    // memory holds is unchanged (unlike MADV_DONTNEED/MADV_FREE, which may discard contents),
    // so no Rust reference can observe a difference. A failure (EINVAL before Linux 5.14,
    // ENOMEM under memory pressure) leaves everything as it was and is ignored: the pages then
    // fault on first touch as usual.
    let _ = unsafe { libc::madvise(first as *mut libc::c_void, len, MADV_POPULATE_WRITE) };
}

#[cfg(not(target_os = "linux"))]
fn prefault(_start: usize, _bytes: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_has_the_requested_room_at_every_size_around_the_prefault_threshold() {
        for len in [
            0,
            1,
            PREFAULT_MIN_BYTES / 8 - 1,
            PREFAULT_MIN_BYTES / 8 + 1,
            (8 << 20) / 8 + 3,
        ] {
            let mut v = storage(len).unwrap();
            assert!(v.is_empty() && v.capacity() >= len, "len {len}");
            // Filling it writes every value (through the advised range) without reallocating.
            let before = v.as_ptr();
            v.extend((0..len).map(|i| i as f64));
            assert_eq!(v.as_ptr(), before);
            assert!(v
                .iter()
                .enumerate()
                .all(|(i, &x)| x.to_bits() == (i as f64).to_bits()));
        }
    }

    /// The hook runs when, and only when, a run does not fit, and the run is still refused
    /// when releasing did not make room.
    #[test]
    fn the_release_hook_runs_before_a_refusal() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        static CALLS: AtomicUsize = AtomicUsize::new(0);
        fn count() {
            CALLS.fetch_add(1, Ordering::SeqCst);
        }
        // The only test of this binary that registers a hook.
        assert!(set_memory_release_hook(count));
        assert!(!set_memory_release_hook(count));
        check_fits(1000, 4).unwrap();
        // Just past the threshold the budget is read (and this machine has room).
        check_fits((TRAJECTORY_ALWAYS_FITS_BYTES / 8) as usize + 1, 1).unwrap();
        assert_eq!(CALLS.load(Ordering::SeqCst), 0);
        // 2^60 samples of 16 values: 2^67 bytes, more than any machine has.
        assert!(matches!(
            check_fits(1 << 60, 16),
            Err(Error::TrajectoryTooLarge { .. })
        ));
        assert_eq!(CALLS.load(Ordering::SeqCst), 1);
    }

    #[test]
    fn an_impossible_block_is_an_error_not_an_abort() {
        assert!(matches!(
            storage(usize::MAX / 16),
            Err(Error::TrajectoryTooLarge { .. })
        ));
    }
}
