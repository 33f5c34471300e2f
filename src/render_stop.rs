//! Stopping a progressive render early with a complete image: on a signal (Ctrl-C, SIGTERM,
//! SIGHUP) or at a time limit, the render starts no new tile and returns what it has.
//! A second signal quits at once (`output::cleanup` removes the temporary files).

use std::sync::atomic::{AtomicI32, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

/// Why a render stopped before its last sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// The signal's number (SIGINT 2, SIGTERM 15, SIGHUP 1).
    Signal(i32),
    TimeLimit,
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StopReason::Signal(2) => write!(f, "interrupted (Ctrl-C)"),
            StopReason::Signal(15) => write!(f, "interrupted (SIGTERM)"),
            StopReason::Signal(n) => write!(f, "interrupted (signal {n})"),
            StopReason::TimeLimit => write!(f, "--time-limit reached"),
        }
    }
}

/// When a render should stop early: a flag the signal handler sets, and a deadline.
#[derive(Clone, Debug, Default)]
pub struct Stop {
    signal: Arc<AtomicI32>,
    deadline: Option<Instant>,
}

impl Stop {
    /// Stops at `deadline` (if any) or on a signal, once `watch`ed.
    pub fn new(deadline: Option<Instant>) -> Self {
        Stop { signal: Arc::default(), deadline }
    }

    /// Why to stop now, if so.
    pub fn requested(&self) -> Option<StopReason> {
        match self.signal.load(Ordering::Relaxed) {
            0 => self.deadline.filter(|d| Instant::now() >= *d).map(|_| StopReason::TimeLimit),
            signal => Some(StopReason::Signal(signal)),
        }
    }

    /// Records a stop request (as the signal handler does).
    pub fn request(&self, signal: i32) {
        self.signal.store(signal, Ordering::Relaxed);
    }

    /// Makes signals stop this render instead of the process, until `unwatch`.
    pub fn watch(&self) {
        *watched() = Some(self.signal.clone());
    }

    pub fn unwatch(&self) {
        *watched() = None;
    }
}

static WATCHED: Mutex<Option<Arc<AtomicI32>>> = Mutex::new(None);

fn watched() -> std::sync::MutexGuard<'static, Option<Arc<AtomicI32>>> {
    WATCHED.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Called by the signal thread: `true` if a watched render takes the signal as a request to
/// stop (the first signal while one renders), `false` if the process should quit.
pub(crate) fn take_signal(signal: i32) -> bool {
    match watched().as_ref() {
        Some(flag) => {
            flag.compare_exchange(0, signal, Ordering::Relaxed, Ordering::Relaxed).is_ok()
        }
        None => false,
    }
}
