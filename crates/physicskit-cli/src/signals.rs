//! Stopping a run on Ctrl-C (SIGINT), SIGTERM or SIGHUP without leaving a file behind.
//!
//! A signal only records its number; the integration's observer reads it every
//! [`OBSERVE_EVERY`](crate::progress::OBSERVE_EVERY) steps and stops the run, `simulate`
//! returns an error, and the temporary output file is deleted as on any other error. The exit
//! status is then `128 + signal number`, as a shell reports a process the signal killed: 130
//! for SIGINT, 143 for SIGTERM, 129 for SIGHUP. A second signal, for whatever is slow to reach
//! the next check, ends the process at once with the same status (the temporary file may then
//! remain, as after SIGKILL).
//!
//! Built on `signal-hook`'s flags rather than the `ctrlc` crate (used before for SIGINT
//! only): its handlers are a lock-free store into an atomic, it tells which signal arrived (so
//! SIGTERM exits with 143, not with SIGINT's 130, which `ctrlc`'s single "termination"
//! handler cannot tell apart), and it provides the second-signal escalation.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

#[cfg(unix)]
use signal_hook::consts::signal::SIGHUP;
use signal_hook::consts::signal::{SIGINT, SIGTERM};

/// The signals that stop a run.
#[cfg(unix)]
const STOP_SIGNALS: [i32; 3] = [SIGINT, SIGTERM, SIGHUP];
#[cfg(not(unix))]
const STOP_SIGNALS: [i32; 2] = [SIGINT, SIGTERM];

/// The number of the last stopping signal received, or 0.
#[derive(Debug, Clone)]
pub struct Stop(Arc<AtomicUsize>);

impl Stop {
    /// Installs the handlers. A signal whose handler cannot be installed keeps its default
    /// action (the process ends at once, less tidily).
    pub fn install() -> Self {
        let received = Arc::new(AtomicUsize::new(0));
        let armed = Arc::new(AtomicBool::new(false));
        for signal in STOP_SIGNALS {
            // The escalation must be registered first: on the first signal `armed` is still
            // false when it runs, and the next registration then arms it.
            let status = 128 + signal;
            let _ = signal_hook::flag::register_conditional_shutdown(
                signal,
                status,
                Arc::clone(&armed),
            );
            let _ = signal_hook::flag::register(signal, Arc::clone(&armed));
            let _ =
                signal_hook::flag::register_usize(signal, Arc::clone(&received), signal as usize);
        }
        Self(received)
    }

    /// Whether a stopping signal has arrived.
    pub fn requested(&self) -> bool {
        self.0.load(Ordering::Relaxed) != 0
    }

    /// `128 + signal number` once a stopping signal has arrived.
    pub fn exit_status(&self) -> Option<u8> {
        match self.0.load(Ordering::Relaxed) {
            0 => None,
            signal => u8::try_from(128 + signal).ok(),
        }
    }

    /// The signal's name, for the error line.
    pub fn name(&self) -> &'static str {
        match self.0.load(Ordering::Relaxed) as i32 {
            SIGINT => "SIGINT",
            SIGTERM => "SIGTERM",
            #[cfg(unix)]
            SIGHUP => "SIGHUP",
            _ => "a signal",
        }
    }
}
