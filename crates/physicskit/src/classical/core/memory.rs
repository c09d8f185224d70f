//! Trajectory storage: refusing what would not fit in memory before allocating it, and
//! allocating the rest so that filling it is cheap.

use super::error::{Error, Result};

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

/// Checks that `samples * values_per_sample` f64 values fit in memory.
///
/// # Errors
/// [`Error::TrajectoryTooLarge`].
pub(crate) fn check_fits(samples: usize, values_per_sample: usize) -> Result<()> {
    let bytes = samples as u128 * values_per_sample as u128 * 8;
    // Without a reading, the address space is the limit (allocation is then also checked with
    // `try_reserve`).
    let available = available_bytes().unwrap_or(isize::MAX as u128);
    let budget = (available as f64 * MAX_FRACTION_OF_AVAILABLE) as u128;
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

/// Smallest allocation worth backing with huge pages: two of them (2 MiB each on x86-64 and
/// most aarch64 kernels), so at least one aligned huge page lies inside.
const HUGE_PAGE_MIN_BYTES: usize = 4 << 20;

/// An empty vector with room for `len` values, for storage filled once, front to back.
///
/// Nothing is written up front: neither `vec![0.0; len]` (`calloc` zeroes blocks it reuses
/// from the heap: on a repeated 2-dof run that `memset` cost as much as the steps) nor an
/// explicit fill. Blocks of 4 MiB and more are advised to be backed by transparent huge pages:
/// first touch then faults once per 2 MiB instead of once per 4 KiB. Measured on the issue-7
/// workloads (1e5 samples stored, best of 3): pendulum swarm 8.6 -> 6.3 us/step, harmonic
/// chain 320 -> 205 ns/step, sine-Gordon 4.3 -> 3.4 us/step. The advice is a hint: where the
/// kernel ignores it (THP disabled, another OS), the vector is the same, only slower to fill.
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
    if bytes >= HUGE_PAGE_MIN_BYTES {
        advise_huge_pages(spare.as_ptr() as usize, bytes);
    }
    Ok(v)
}

#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn advise_huge_pages(start: usize, bytes: usize) {
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
    // SAFETY: the range [first, first + len) lies inside the caller's allocation, and
    // MADV_HUGEPAGE only sets how the kernel backs it: it neither unmaps nor changes contents
    // (unlike MADV_DONTNEED/MADV_FREE), so no Rust reference can observe a difference. A
    // failure (EINVAL where THP is compiled out) leaves everything as it was, so it is ignored.
    let _ = unsafe { libc::madvise(first as *mut libc::c_void, len, libc::MADV_HUGEPAGE) };
}

#[cfg(not(target_os = "linux"))]
fn advise_huge_pages(_start: usize, _bytes: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_has_the_requested_room_at_every_size_around_the_huge_page_threshold() {
        for len in [
            0,
            1,
            HUGE_PAGE_MIN_BYTES / 8 - 1,
            HUGE_PAGE_MIN_BYTES / 8 + 3,
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

    #[test]
    fn an_impossible_block_is_an_error_not_an_abort() {
        assert!(matches!(
            storage(usize::MAX / 16),
            Err(Error::TrajectoryTooLarge { .. })
        ));
    }
}
