//! Bounded shutdown of the shell's threads: a thread that does not end within its bound
//! is named in an error instead of being waited for forever (a thread blocked on a lock,
//! a socket or a peer must never keep a process from exiting).

use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a shell waits for each of its threads to end once told to stop. Every
/// thread of the shells checks its stop flag at least every 100 ms, so a thread still
/// running after this is stuck.
pub const SHUTDOWN_BOUND: Duration = Duration::from_secs(5);

/// Why a thread did not end cleanly.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShutdownError {
    /// Still running after the bound (left behind; the process may exit without it).
    #[error("thread `{name}` did not stop within {bound:?} (left running)")]
    Stuck {
        /// The thread's name.
        name: String,
        /// How long it was given.
        bound: Duration,
    },
    /// It panicked.
    #[error("thread `{name}` panicked")]
    Panicked {
        /// The thread's name.
        name: String,
    },
}

impl From<ShutdownError> for std::io::Error {
    fn from(e: ShutdownError) -> Self {
        std::io::Error::other(e.to_string())
    }
}

/// Waits up to `bound` for `handle`'s thread to end and returns what it returned. A
/// thread still running after `bound` is left behind (detached) and reported by name.
pub fn join_within<T>(handle: JoinHandle<T>, bound: Duration) -> Result<T, ShutdownError> {
    let name = handle.thread().name().unwrap_or("(unnamed)").to_string();
    let deadline = Instant::now() + bound;
    while !handle.is_finished() {
        if Instant::now() >= deadline {
            tracing::error!(thread = %name, "did not stop within {bound:?}; left running");
            return Err(ShutdownError::Stuck { name, bound });
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    handle.join().map_err(|_| ShutdownError::Panicked { name })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;

    #[test]
    fn a_thread_that_ends_is_joined_with_its_result() {
        let h = std::thread::spawn(|| 7);
        assert_eq!(join_within(h, Duration::from_secs(5)), Ok(7));
    }

    #[test]
    fn a_stuck_thread_is_named_and_left_behind() {
        let release = Arc::new(AtomicBool::new(false));
        let r = release.clone();
        let h = std::thread::Builder::new()
            .name("stuck-one".into())
            .spawn(move || {
                while !r.load(Ordering::Relaxed) {
                    std::thread::sleep(Duration::from_millis(1));
                }
            })
            .unwrap();
        let t0 = Instant::now();
        let e = join_within(h, Duration::from_millis(50)).unwrap_err();
        assert!(t0.elapsed() < Duration::from_secs(2));
        assert_eq!(
            e,
            ShutdownError::Stuck {
                name: "stuck-one".into(),
                bound: Duration::from_millis(50)
            }
        );
        assert!(e.to_string().contains("`stuck-one` did not stop"));
        release.store(true, Ordering::Relaxed);
    }

    #[test]
    fn a_panicking_thread_is_named() {
        let h = std::thread::Builder::new()
            .name("boom".into())
            .spawn(|| panic!("on purpose"))
            .unwrap();
        assert_eq!(
            join_within(h, Duration::from_secs(5)),
            Err(ShutdownError::Panicked {
                name: "boom".into()
            })
        );
    }
}
