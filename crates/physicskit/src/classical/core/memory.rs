//! Refusing trajectories that would not fit in memory, before allocating them.

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
