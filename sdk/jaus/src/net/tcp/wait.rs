//! Waiting for any of the transport's sockets: `poll(2)` on Linux, short sleeps
//! elsewhere.

use std::net::{TcpListener, TcpStream};
use std::time::Duration;

/// Waits at most `timeout` until the listener has a connection, a stream has bytes (or
/// an error, or its end), or a stream flagged `true` can take bytes. A signal ends the
/// wait early, which the caller takes as a spurious wake-up.
#[cfg(target_os = "linux")]
pub(super) fn ready(
    listener: Option<&TcpListener>,
    conns: &[(&TcpStream, bool)],
    timeout: Duration,
) -> std::io::Result<()> {
    use nix::poll::{poll, PollFd, PollFlags, PollTimeout};
    use std::os::fd::AsFd;
    let mut fds: Vec<PollFd<'_>> = Vec::with_capacity(conns.len() + 1);
    if let Some(l) = listener {
        fds.push(PollFd::new(l.as_fd(), PollFlags::POLLIN));
    }
    for (s, write) in conns {
        let mut events = PollFlags::POLLIN;
        if *write {
            events |= PollFlags::POLLOUT;
        }
        fds.push(PollFd::new(s.as_fd(), events));
    }
    // Whole milliseconds, rounded up so that a short wait is not a busy loop.
    let ms = timeout.as_micros().div_ceil(1000).min(60_000) as u16;
    match poll(&mut fds, PollTimeout::from(ms)) {
        Ok(_) | Err(nix::errno::Errno::EINTR) => Ok(()),
        Err(e) => Err(std::io::Error::from(e)),
    }
}

/// Elsewhere: a sleep of at most 2 ms (the caller polls the sockets again).
#[cfg(not(target_os = "linux"))]
pub(super) fn ready(
    _listener: Option<&TcpListener>,
    _conns: &[(&TcpStream, bool)],
    timeout: Duration,
) -> std::io::Result<()> {
    std::thread::sleep(timeout.min(Duration::from_millis(2)));
    Ok(())
}
