//! Reading and writing datagrams for the I/O shell: a receiver that spins briefly after
//! each datagram before it sleeps in the kernel, and reads and writes several datagrams
//! per system call where the OS offers it (`recvmmsg` on Linux, through `nix`);
//! elsewhere, and with a batch of 1, one `recv_from` per datagram.
//!
//! Sends stay one `send_to` per datagram: `nix`'s `sendmmsg` reports how many were sent
//! only through an iterator that reads address slots a send never fills.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use super::IoOptions;

/// Largest datagram read (JUDP or OPC framing plus a full 4096-byte packet).
pub(super) const MAX_DATAGRAM: usize = 8 + 4096 + 64;

/// Most datagrams one system call reads.
pub const MAX_BATCH: usize = 64;

/// Receives datagrams on one socket. After a datagram it keeps reading without blocking
/// for [`IoOptions::spin`] (the next datagram of a burst is taken without a wake-up);
/// otherwise it blocks until the wait is over. The socket's mode and read timeout are
/// changed only when they must be (each change is a system call).
#[derive(Debug)]
pub(super) struct Receiver {
    spin: Duration,
    /// `batch` slots of [`MAX_DATAGRAM`] bytes.
    buf: Vec<u8>,
    /// Length and sender of each datagram of the last read, in slot order.
    got: Vec<(usize, SocketAddr)>,
    last: Option<Instant>,
    nonblocking: bool,
    timeout: Option<Duration>,
    #[cfg(target_os = "linux")]
    headers: Option<nix::sys::socket::MultiHeaders<nix::sys::socket::SockaddrStorage>>,
}

impl Receiver {
    pub(super) fn new(io: &IoOptions) -> Self {
        let batch = io.batch.clamp(1, MAX_BATCH);
        Self {
            spin: io.spin,
            buf: vec![0; batch * MAX_DATAGRAM],
            got: Vec::with_capacity(batch),
            last: None,
            nonblocking: false,
            timeout: None,
            #[cfg(target_os = "linux")]
            headers: (batch > 1).then(|| nix::sys::socket::MultiHeaders::preallocate(batch, None)),
        }
    }

    /// Waits up to `wait` (from `now`) for datagrams; returns how many were read (0
    /// when the wait ended without one). Read them with [`datagram`](Self::datagram).
    pub(super) fn recv(
        &mut self,
        socket: &UdpSocket,
        now: Instant,
        wait: Duration,
    ) -> std::io::Result<usize> {
        self.got.clear();
        if let Some(last) = self
            .last
            .filter(|l| now.saturating_duration_since(*l) < self.spin)
        {
            if !self.nonblocking {
                socket.set_nonblocking(true)?;
                self.nonblocking = true;
            }
            let until = (last + self.spin).min(now + wait);
            loop {
                match self.read(socket, false) {
                    Ok(n) => return Ok(self.received(n)),
                    // A signal: the caller looks at its stop flag.
                    Err(e) if e.kind() == ErrorKind::Interrupted => return Ok(0),
                    Err(e) if e.kind() == ErrorKind::WouldBlock => {
                        if Instant::now() >= until {
                            return Ok(0);
                        }
                        std::hint::spin_loop();
                    }
                    Err(e) => return Err(e),
                }
            }
        }
        if self.nonblocking {
            socket.set_nonblocking(false)?;
            self.nonblocking = false;
        }
        // Whole milliseconds, rounded down (an early wake-up only loops once more): the
        // timeout changes, and costs a system call, only when the millisecond does.
        let t = if wait >= Duration::from_millis(1) {
            Duration::from_millis(wait.as_millis() as u64)
        } else {
            wait.max(Duration::from_micros(1))
        };
        if self.timeout != Some(t) {
            socket.set_read_timeout(Some(t))?;
            self.timeout = Some(t);
        }
        match self.read(socket, true) {
            Ok(n) => Ok(self.received(n)),
            Err(e)
                if matches!(
                    e.kind(),
                    ErrorKind::WouldBlock | ErrorKind::TimedOut | ErrorKind::Interrupted
                ) =>
            {
                Ok(0)
            }
            Err(e) => Err(e),
        }
    }

    fn received(&mut self, n: usize) -> usize {
        if n > 0 {
            self.last = Some(Instant::now());
        }
        n
    }

    /// The `i`-th datagram of the last [`recv`](Self::recv): its sender and bytes.
    pub(super) fn datagram(&self, i: usize) -> (SocketAddr, &[u8]) {
        let (len, peer) = self.got[i];
        let at = i * MAX_DATAGRAM;
        (peer, &self.buf[at..at + len])
    }

    /// One read: a batch where the OS offers it, else one datagram. `block`: wait for
    /// the first datagram (the socket's timeout applies), the rest are taken only if
    /// already there.
    fn read(&mut self, socket: &UdpSocket, block: bool) -> std::io::Result<usize> {
        #[cfg(target_os = "linux")]
        if let Some(headers) = self.headers.as_mut() {
            return read_batch(socket, headers, &mut self.buf, &mut self.got, block);
        }
        let _ = block; // the socket's mode decides
        let (n, peer) = socket.recv_from(&mut self.buf[..MAX_DATAGRAM])?;
        self.got.push((n, peer));
        Ok(1)
    }
}

/// `recvmmsg` into the slots of `buf`.
#[cfg(target_os = "linux")]
fn read_batch(
    socket: &UdpSocket,
    headers: &mut nix::sys::socket::MultiHeaders<nix::sys::socket::SockaddrStorage>,
    buf: &mut [u8],
    got: &mut Vec<(usize, SocketAddr)>,
    block: bool,
) -> std::io::Result<usize> {
    use nix::sys::socket::{recvmmsg, MsgFlags};
    use std::io::IoSliceMut;
    use std::os::fd::AsRawFd;
    let slots = buf.len() / MAX_DATAGRAM;
    let mut chunks = buf.chunks_exact_mut(MAX_DATAGRAM);
    // On the stack: no allocation per read. Slots past `slots` are empty and unused.
    let mut iovs: [[IoSliceMut<'_>; 1]; MAX_BATCH] =
        std::array::from_fn(|_| [IoSliceMut::new(chunks.next().unwrap_or_default())]);
    let flags = if block {
        MsgFlags::MSG_WAITFORONE
    } else {
        MsgFlags::MSG_DONTWAIT
    };
    let results = recvmmsg(
        socket.as_raw_fd(),
        headers,
        iovs[..slots].iter_mut(),
        flags,
        None,
    )
    .map_err(std::io::Error::from)?;
    for r in results {
        // A datagram without an IPv4/IPv6 sender cannot come on a UDP socket; such a
        // slot would be skipped (its sender unknown) rather than misattributed.
        let peer = r.address.as_ref().and_then(socket_addr);
        got.push((r.bytes, peer.unwrap_or(SocketAddr::from(([0, 0, 0, 0], 0)))));
    }
    Ok(got.len())
}

#[cfg(target_os = "linux")]
fn socket_addr(a: &nix::sys::socket::SockaddrStorage) -> Option<SocketAddr> {
    if let Some(v4) = a.as_sockaddr_in() {
        return Some(SocketAddr::V4(std::net::SocketAddrV4::from(*v4)));
    }
    a.as_sockaddr_in6()
        .map(|v6| SocketAddr::V6(std::net::SocketAddrV6::from(*v6)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair() -> (UdpSocket, UdpSocket) {
        let a = UdpSocket::bind("127.0.0.1:0").unwrap();
        let b = UdpSocket::bind("127.0.0.1:0").unwrap();
        (a, b)
    }

    /// Every datagram sent is read once, in order, with its sender, whatever the batch.
    #[test]
    fn reads_every_datagram_in_order_with_its_sender() {
        for batch in [1, 4, 32] {
            let (rx, tx) = pair();
            let to = rx.local_addr().unwrap();
            for i in 0..10u8 {
                tx.send_to(&[i; 3], to).unwrap();
            }
            let mut r = Receiver::new(&IoOptions {
                spin: Duration::ZERO,
                batch,
            });
            let mut seen = Vec::new();
            let mut reads = 0;
            while seen.len() < 10 && reads < 100 {
                reads += 1;
                let n = r
                    .recv(&rx, Instant::now(), Duration::from_millis(200))
                    .unwrap();
                assert!(n <= batch, "batch {batch}: {n} in one read");
                for i in 0..n {
                    let (peer, bytes) = r.datagram(i);
                    assert_eq!(peer, tx.local_addr().unwrap());
                    seen.push(bytes.to_vec());
                }
            }
            let expected: Vec<Vec<u8>> = (0..10u8).map(|i| vec![i; 3]).collect();
            assert_eq!(seen, expected, "batch {batch}");
            if cfg!(target_os = "linux") && batch == 32 {
                // All ten were waiting: one recvmmsg takes them.
                assert_eq!(reads, 1);
            }
        }
    }

    /// A full-size datagram fits a slot, and the slot after it is not overwritten.
    #[test]
    fn full_size_datagrams_keep_their_slots() {
        let (rx, tx) = pair();
        let to = rx.local_addr().unwrap();
        let big: Vec<u8> = (0..MAX_DATAGRAM).map(|i| i as u8).collect();
        tx.send_to(&big, to).unwrap();
        tx.send_to(b"next", to).unwrap();
        let mut r = Receiver::new(&IoOptions::default());
        let mut seen = Vec::new();
        while seen.len() < 2 {
            let n = r
                .recv(&rx, Instant::now(), Duration::from_millis(200))
                .unwrap();
            assert!(n > 0, "timed out");
            seen.extend((0..n).map(|i| r.datagram(i).1.to_vec()));
        }
        assert_eq!(seen[0], big);
        assert_eq!(seen[1], b"next");
    }

    /// No datagram: the wait ends with none read, not an error.
    #[test]
    fn a_quiet_socket_times_out_with_nothing() {
        let (rx, _tx) = pair();
        for io in [
            IoOptions::default(),
            IoOptions {
                spin: Duration::ZERO,
                batch: 1,
            },
        ] {
            let mut r = Receiver::new(&io);
            assert_eq!(
                r.recv(&rx, Instant::now(), Duration::from_millis(2))
                    .unwrap(),
                0
            );
        }
    }

    /// While spinning after a datagram the socket is polled without blocking, and a
    /// datagram arriving then is read; once the spin is over the receiver blocks again
    /// and still reads.
    #[test]
    fn spinning_and_then_blocking_both_read() {
        let (rx, tx) = pair();
        let to = rx.local_addr().unwrap();
        let mut r = Receiver::new(&IoOptions {
            spin: Duration::from_secs(5),
            batch: 1,
        });
        tx.send_to(b"first", to).unwrap();
        assert_eq!(
            r.recv(&rx, Instant::now(), Duration::from_secs(1)).unwrap(),
            1
        );
        let sender = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(20));
            tx.send_to(b"second", to).unwrap();
            tx
        });
        assert_eq!(
            r.recv(&rx, Instant::now(), Duration::from_secs(2)).unwrap(),
            1
        );
        assert!(r.nonblocking, "the second read was a spin");
        assert_eq!(r.datagram(0).1, b"second");
        let tx = sender.join().unwrap();
        // Past the spin (as if 6 s had gone by): back to a blocking read.
        r.last = Some(Instant::now() - Duration::from_secs(6));
        tx.send_to(b"third", to).unwrap();
        assert_eq!(
            r.recv(&rx, Instant::now(), Duration::from_secs(1)).unwrap(),
            1
        );
        assert!(!r.nonblocking);
        assert_eq!(r.datagram(0).1, b"third");
    }
}
