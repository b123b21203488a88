//! Reading and writing datagrams for the I/O shell: a receiver that spins briefly after
//! each datagram before it sleeps in the kernel, and reads and writes several datagrams
//! per system call where the OS offers it (`recvmmsg` on Linux, through `nix`);
//! elsewhere, and with a batch of 1, one `recv_from` per datagram.
//!
//! Sends go out several per system call on Linux: runs of equal datagrams to one peer
//! segmentation-offloaded (UDP GSO), the rest by `sendmmsg` (called through `libc`:
//! `nix`'s wrapper reports how many were sent only through an iterator that reads
//! address slots a send never fills); one `send_to` each elsewhere.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use super::{Datagram, IoOptions};

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

/// Sends datagrams several per system call where the OS offers it. On Linux, a run of
/// datagrams to the same peer with the same length (a burst of replies to one client)
/// leaves as one segmentation-offloaded send (UDP GSO: one trip through the stack for
/// the run, cut into the same datagrams below it), the rest in `sendmmsg` batches;
/// elsewhere one `send_to` each. A kernel or route that refuses offload (an old kernel,
/// a device without checksum offload, a datagram larger than the path's MTU) is
/// remembered and the socket goes on without it.
#[derive(Debug)]
pub(super) struct Sender {
    /// Whether segmentation offload is still tried on this socket.
    gso: bool,
}

impl Default for Sender {
    fn default() -> Self {
        Self {
            gso: cfg!(target_os = "linux"),
        }
    }
}

/// Most datagrams in one offloaded send (the kernel's limit is 64 segments of at most
/// 64 KiB in all).
#[cfg(target_os = "linux")]
const GSO_SEGMENTS: usize = 64;
#[cfg(target_os = "linux")]
const GSO_BYTES: usize = 65_000;

impl Sender {
    /// Sends `ds` on `socket` in order, telling `done` the outcome of each. A datagram
    /// the kernel refuses gets its error and the rest are still sent, as one `send_to`
    /// each would; a refused offloaded run gets the error for each of its datagrams.
    pub(super) fn send_all(
        &mut self,
        socket: &UdpSocket,
        ds: &[Datagram],
        mut done: impl FnMut(usize, std::io::Result<()>),
    ) {
        let mut at = 0;
        while at < ds.len() {
            #[cfg(target_os = "linux")]
            {
                let run = if self.gso { same_run(&ds[at..]) } else { 1 };
                if run > 1 {
                    match send_segmented(socket, &ds[at..at + run]) {
                        Ok(()) => {
                            for i in at..at + run {
                                done(i, Ok(()));
                            }
                            at += run;
                        }
                        Err(e) if offload_refused(&e) => {
                            tracing::debug!(
                                "UDP segmentation offload refused ({e}): sending one by one"
                            );
                            self.gso = false;
                        }
                        Err(e) => {
                            for i in at..at + run {
                                done(i, Err(copy_error(&e)));
                            }
                            at += run;
                        }
                    }
                    continue;
                }
                // Up to the next run worth offloading, in `sendmmsg` batches.
                let mut end = at + 1;
                while end < ds.len()
                    && end - at < MAX_BATCH
                    && (!self.gso || same_run(&ds[end..]) < 2)
                {
                    end += 1;
                }
                let sent = if end - at > 1 {
                    send_batch(socket, &ds[at..end])
                } else {
                    socket.send_to(&ds[at].bytes, ds[at].to).map(|_| 1)
                };
                at = report(at, sent, &mut done);
            }
            #[cfg(not(target_os = "linux"))]
            {
                let sent = socket.send_to(&ds[at].bytes, ds[at].to).map(|_| 1);
                at = report(at, sent, &mut done);
            }
        }
    }
}

/// Reports the outcome of a send of `sent` datagrams from `at` (or the error of the
/// one at `at`); where the next send starts.
fn report(
    at: usize,
    sent: std::io::Result<usize>,
    done: &mut impl FnMut(usize, std::io::Result<()>),
) -> usize {
    match sent {
        Ok(n) => {
            for i in at..at + n {
                done(i, Ok(()));
            }
            at + n
        }
        // The error is the first unsent datagram's (sendmmsg returns it when that one
        // was the first of the call, and a count otherwise).
        Err(e) => {
            done(at, Err(e));
            at + 1
        }
    }
}

/// How many datagrams from the first have its peer and length (at most what one
/// offloaded send carries).
#[cfg(target_os = "linux")]
fn same_run(ds: &[Datagram]) -> usize {
    let first = &ds[0];
    let len = first.bytes.len();
    if len == 0 {
        return 1;
    }
    let most = GSO_SEGMENTS.min(GSO_BYTES / len);
    ds.iter()
        .take(most)
        .take_while(|d| d.to == first.to && d.bytes.len() == len)
        .count()
        .max(1)
}

/// One send of datagrams of equal length to one peer, cut by the kernel (UDP_SEGMENT).
#[cfg(target_os = "linux")]
fn send_segmented(socket: &UdpSocket, ds: &[Datagram]) -> std::io::Result<()> {
    use nix::sys::socket::{sendmsg, ControlMessage, MsgFlags, SockaddrStorage};
    use std::io::IoSlice;
    use std::os::fd::AsRawFd;
    let size = u16::try_from(ds[0].bytes.len()).map_err(|_| std::io::ErrorKind::InvalidInput)?;
    let mut slices: [IoSlice<'_>; GSO_SEGMENTS] = [IoSlice::new(&[]); GSO_SEGMENTS];
    for (s, d) in slices.iter_mut().zip(ds) {
        *s = IoSlice::new(&d.bytes);
    }
    let to = SockaddrStorage::from(ds[0].to);
    sendmsg(
        socket.as_raw_fd(),
        &slices[..ds.len()],
        &[ControlMessage::UdpGsoSegments(&size)],
        MsgFlags::empty(),
        Some(&to),
    )
    .map(drop)
    .map_err(std::io::Error::from)
}

/// Whether a send failed because offload is not available here (rather than for a
/// reason that would fail the datagrams one by one too).
#[cfg(target_os = "linux")]
fn offload_refused(e: &std::io::Error) -> bool {
    use nix::errno::Errno;
    matches!(
        e.raw_os_error().map(Errno::from_raw),
        Some(Errno::EIO | Errno::EINVAL | Errno::ENOPROTOOPT | Errno::EOPNOTSUPP | Errno::EMSGSIZE)
    )
}

/// The same error again, for each datagram of a refused run.
#[cfg(target_os = "linux")]
fn copy_error(e: &std::io::Error) -> std::io::Error {
    e.raw_os_error().map_or_else(
        || std::io::Error::new(e.kind(), e.to_string()),
        std::io::Error::from_raw_os_error,
    )
}

/// One `sendmmsg` of `ds` (1 to [`MAX_BATCH`] datagrams): how many the kernel took
/// (at least one), or the error of the first.
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn send_batch(socket: &UdpSocket, ds: &[Datagram]) -> std::io::Result<usize> {
    use nix::sys::socket::{SockaddrLike, SockaddrStorage};
    use std::os::fd::AsRawFd;
    let n = ds.len().min(MAX_BATCH);
    let addrs: [SockaddrStorage; MAX_BATCH] = std::array::from_fn(|i| {
        SockaddrStorage::from(
            ds.get(i)
                .map_or(SocketAddr::from(([0, 0, 0, 0], 0)), |d| d.to),
        )
    });
    let iovs: [libc::iovec; MAX_BATCH] = std::array::from_fn(|i| libc::iovec {
        iov_base: ds
            .get(i)
            .map_or(std::ptr::null_mut(), |d| d.bytes.as_ptr().cast_mut().cast()),
        iov_len: ds.get(i).map_or(0, |d| d.bytes.len()),
    });
    // SAFETY: `mmsghdr` is a C struct of integers and raw pointers, for which all-zero
    // bytes are a valid value (null pointers, zero lengths and flags).
    let mut headers: [libc::mmsghdr; MAX_BATCH] = unsafe { std::mem::zeroed() };
    for (h, (a, iov)) in headers
        .iter_mut()
        .zip(addrs.iter().zip(iovs.iter()))
        .take(n)
    {
        h.msg_hdr.msg_name = a.as_ptr().cast_mut().cast();
        h.msg_hdr.msg_namelen = a.len();
        h.msg_hdr.msg_iov = std::ptr::from_ref(iov).cast_mut();
        h.msg_hdr.msg_iovlen = 1;
    }
    // SAFETY: the first `n` headers point at `addrs[i]` (a socket address of
    // `msg_namelen` bytes) and at `iovs[i]`, which points at `ds[i].bytes` (`iov_len`
    // bytes); all of them live on this stack frame or in `ds` until the call returns and
    // none is moved or freed during it. The kernel only reads the names, the iovecs and
    // the bytes (it never writes through these pointers for a send) and writes
    // `msg_len` of the headers, which are ours and mutable. `n` ≤ the array's length.
    let sent = unsafe { libc::sendmmsg(socket.as_raw_fd(), headers.as_mut_ptr(), n as u32, 0) };
    if sent < 0 {
        return Err(std::io::Error::last_os_error());
    }
    if sent == 0 {
        // Not expected (sendmmsg reports an error when it sends nothing): the first
        // one alone then says what happened to it.
        return socket.send_to(&ds[0].bytes, ds[0].to).map(|_| 1);
    }
    Ok(sent as usize)
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

    /// Sends go out in order, each reported once; one the kernel refuses (an IPv6
    /// destination on an IPv4 socket) gets its error and those after it still go.
    #[test]
    fn send_all_sends_in_order_and_reports_each() {
        let (rx, tx) = pair();
        let to = rx.local_addr().unwrap();
        let bad: SocketAddr = "[::1]:9".parse().unwrap();
        let ds: Vec<Datagram> = (0..(MAX_BATCH as u8 + 10))
            .map(|i| Datagram {
                to: if i == 4 { bad } else { to },
                bytes: vec![i; 1 + usize::from(i)],
                via: super::super::Via::Network,
            })
            .collect();
        let mut outcomes = Vec::new();
        Sender::default().send_all(&tx, &ds, |i, r| outcomes.push((i, r.is_ok())));
        let expected: Vec<(usize, bool)> = (0..ds.len()).map(|i| (i, i != 4)).collect();
        assert_eq!(outcomes, expected);
        let mut r = Receiver::new(&IoOptions::default());
        let mut seen = Vec::new();
        while seen.len() < ds.len() - 1 {
            let n = r
                .recv(&rx, Instant::now(), Duration::from_millis(500))
                .unwrap();
            assert!(n > 0, "timed out after {} datagrams", seen.len());
            seen.extend((0..n).map(|i| r.datagram(i).1.to_vec()));
        }
        let sent: Vec<Vec<u8>> = ds
            .iter()
            .filter(|d| d.to == to)
            .map(|d| d.bytes.clone())
            .collect();
        assert_eq!(seen, sent);
    }

    /// Runs of equal datagrams to one peer (offloaded on Linux) arrive as the same
    /// datagrams, in order, between datagrams of other lengths; a run longer than one
    /// offloaded send is split.
    #[test]
    fn runs_of_equal_datagrams_arrive_one_by_one_in_order() {
        let (rx, tx) = pair();
        let to = rx.local_addr().unwrap();
        let mut ds = Vec::new();
        let mut push = |len: usize, tag: u8| {
            ds.push(Datagram {
                to,
                bytes: vec![tag; len],
                via: super::super::Via::Network,
            })
        };
        for i in 0..70u8 {
            push(40, i);
        }
        push(7, 200);
        push(9, 201);
        for i in 0..3u8 {
            push(1200, 210 + i);
        }
        let mut sender = Sender::default();
        let mut outcomes = 0;
        sender.send_all(&tx, &ds, |_, r| {
            r.unwrap();
            outcomes += 1;
        });
        assert_eq!(outcomes, ds.len());
        if cfg!(target_os = "linux") && !sender.gso {
            eprintln!("this kernel refused UDP segmentation offload: sent without it");
        }
        let mut r = Receiver::new(&IoOptions::default());
        let mut seen = Vec::new();
        while seen.len() < ds.len() {
            let n = r
                .recv(&rx, Instant::now(), Duration::from_millis(500))
                .unwrap();
            assert!(n > 0, "timed out after {} datagrams", seen.len());
            for i in 0..n {
                let (peer, bytes) = r.datagram(i);
                assert_eq!(peer, tx.local_addr().unwrap());
                seen.push(bytes.to_vec());
            }
        }
        let sent: Vec<Vec<u8>> = ds.iter().map(|d| d.bytes.clone()).collect();
        assert_eq!(seen, sent);
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
