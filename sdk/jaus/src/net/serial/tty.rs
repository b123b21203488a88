//! The tty: opened without becoming the process's controlling terminal, non-blocking,
//! raw at the asked speed (`nix`'s termios calls: no `unsafe` here), and waited on
//! with `poll(2)`.

use std::fs::File;
use std::os::unix::fs::OpenOptionsExt;
use std::path::Path;
use std::time::Duration;

use nix::sys::termios::{self, BaudRate, ControlFlags, SetArg, SpecialCharacterIndices};

/// The OS's name of `baud` bits per second.
fn speed(baud: u32) -> Option<BaudRate> {
    Some(match baud {
        1200 => BaudRate::B1200,
        2400 => BaudRate::B2400,
        4800 => BaudRate::B4800,
        9600 => BaudRate::B9600,
        19_200 => BaudRate::B19200,
        38_400 => BaudRate::B38400,
        57_600 => BaudRate::B57600,
        115_200 => BaudRate::B115200,
        230_400 => BaudRate::B230400,
        460_800 => BaudRate::B460800,
        921_600 => BaudRate::B921600,
        1_000_000 => BaudRate::B1000000,
        2_000_000 => BaudRate::B2000000,
        _ => return None,
    })
}

/// Opens `path` non-blocking and sets it raw at `baud`.
pub(super) fn open_raw(path: &Path, baud: u32) -> std::io::Result<File> {
    let rate = speed(baud).ok_or_else(|| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{baud} baud is not a speed this OS names (e.g. 9600, 57600, 115200)"),
        )
    })?;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .custom_flags((nix::fcntl::OFlag::O_NOCTTY | nix::fcntl::OFlag::O_NONBLOCK).bits())
        .open(path)?;
    let mut t = termios::tcgetattr(&file).map_err(|e| {
        std::io::Error::new(
            std::io::Error::from(e).kind(),
            format!("not a terminal: {e}"),
        )
    })?;
    termios::cfmakeraw(&mut t);
    t.control_flags |= ControlFlags::CLOCAL | ControlFlags::CREAD;
    t.control_flags &= !(ControlFlags::CSTOPB | ControlFlags::PARENB | ControlFlags::CRTSCTS);
    t.control_chars[SpecialCharacterIndices::VMIN as usize] = 0;
    t.control_chars[SpecialCharacterIndices::VTIME as usize] = 0;
    termios::cfsetspeed(&mut t, rate).map_err(std::io::Error::from)?;
    termios::tcsetattr(&file, SetArg::TCSANOW, &t).map_err(std::io::Error::from)?;
    Ok(file)
}

/// Waits at most `timeout` for bytes to read (or, with `write`, room to write).
pub(super) fn wait(file: &File, write: bool, timeout: Duration) -> std::io::Result<()> {
    use nix::poll::{poll, PollFd, PollFlags, PollTimeout};
    use std::os::fd::AsFd;
    let mut events = PollFlags::POLLIN;
    if write {
        events |= PollFlags::POLLOUT;
    }
    let mut fds = [PollFd::new(file.as_fd(), events)];
    let ms = timeout.as_micros().div_ceil(1000).min(60_000) as u16;
    match poll(&mut fds, PollTimeout::from(ms)) {
        Ok(_) => {
            // A pseudo-terminal without its other side reports POLLHUP at once: wait
            // the time out rather than spin.
            if fds[0]
                .revents()
                .is_some_and(|r| r.contains(PollFlags::POLLHUP))
            {
                std::thread::sleep(timeout.min(Duration::from_millis(20)));
            }
            Ok(())
        }
        Err(nix::errno::Errno::EINTR) => Ok(()),
        Err(e) => Err(std::io::Error::from(e)),
    }
}
