//! Rebuilding large AS5669A messages, with bounded memory.
//!
//! A sender numbers all its packets with one running counter, so a large message is a
//! run of consecutive sequence numbers: a first packet, normal packets, a last packet.
//! The [`As4Reassembler`] keeps, per source id, the messages whose first packet came
//! (a stream each, its packets by offset from the first) and the packets that came
//! before their first (reordering); a packet is filed under the nearest first packet
//! before it. A message is delivered once its first, its last and every packet between
//! are held, never before. Duplicates are counted and dropped; a packet that repeats a
//! sequence number with other bytes replaces the one held (a stale one after the
//! counter wrapped), counted as a restart.
//!
//! The byte and time bounds are the RA 3.3 reassembler's, applied by the same rule
//! (bytes per source and in total, the size of one message, a timeout after the last
//! packet of a source). The bytes held per source and in total count each packet's
//! bytes on the wire (payload + 14), so that packets with empty payloads are bounded
//! too; the message size bound counts the payload bytes a source has in progress. The
//! messages in progress (first packets held) are bounded as well. Every drop is counted
//! in [`ReassemblyStats`].

use std::collections::{BTreeMap, HashMap};
use std::time::Instant;

use super::header::{As4Header, As4Id, As4Packet, DataControl, OVERHEAD};
use crate::net::framing::{ByteBudget, ReassemblyLimits, ReassemblyStats};

/// Limits of the [`As4Reassembler`].
#[derive(Debug, Clone, Copy)]
pub struct As4ReassemblyLimits {
    /// Bytes and time, as for RA 3.3 (defaults there: 1 MiB per message, 2 MiB per
    /// source, 16 MiB in all, 2 s).
    pub bytes: ReassemblyLimits,
    /// Most messages in progress (first packets held, over all sources). Default 256.
    pub max_in_progress: usize,
}

impl Default for As4ReassemblyLimits {
    fn default() -> Self {
        Self {
            bytes: ReassemblyLimits::default(),
            max_in_progress: 256,
        }
    }
}

/// A message whose first packet came: its packets by offset from the first.
#[derive(Debug)]
struct Stream {
    header: As4Header,
    parts: BTreeMap<u16, Vec<u8>>,
    last: Option<u16>,
}

/// A packet held before its first packet came.
#[derive(Debug, PartialEq, Eq)]
struct Early {
    data_control: DataControl,
    payload: Vec<u8>,
}

/// Where a packet goes in a [`Source`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Slot {
    /// A first packet: the stream at its sequence number.
    First,
    /// Stream (by its first sequence number), offset.
    Stream(u16, u16),
    /// With the packets of no stream yet.
    Early,
}

/// What one source id has in progress.
#[derive(Debug)]
struct Source {
    /// Streams by the sequence number of their first packet.
    streams: BTreeMap<u16, Stream>,
    /// Packets of no stream yet, by sequence number.
    early: BTreeMap<u16, Early>,
    /// Bytes held, packets on the wire.
    bytes: usize,
    /// Payload bytes held (the size of what is being rebuilt).
    payload: usize,
    touched: Instant,
}

fn cost(payload: &[u8]) -> usize {
    payload.len() + OVERHEAD
}

/// Rebuilds large AS5669A messages, keyed by source id (see the module documentation).
#[derive(Debug)]
pub struct As4Reassembler {
    budget: ByteBudget<As4Id>,
    max_in_progress: usize,
    in_progress: usize,
    sources: HashMap<As4Id, Source>,
    stats: ReassemblyStats,
}

impl As4Reassembler {
    /// With `limits`.
    pub fn new(limits: As4ReassemblyLimits) -> Self {
        Self {
            budget: ByteBudget::new(limits.bytes),
            max_in_progress: limits.max_in_progress,
            in_progress: 0,
            sources: HashMap::new(),
            stats: ReassemblyStats::default(),
        }
    }

    /// Counters.
    pub fn stats(&self) -> ReassemblyStats {
        self.stats
    }

    /// Bytes held now (packets on the wire).
    pub fn buffered(&self) -> usize {
        self.budget.total()
    }

    /// Messages in progress (first packets held).
    pub fn in_progress(&self) -> usize {
        self.in_progress
    }

    /// The earliest instant a source's incomplete messages time out.
    pub fn next_timeout(&self) -> Option<Instant> {
        self.sources
            .values()
            .map(|s| self.budget.deadline(s.touched))
            .min()
    }

    /// Drops what sources silent for the timeout hold; each message in progress (or a
    /// source's early packets alone) counts one time-out.
    pub fn expire(&mut self, now: Instant) {
        let old: Vec<As4Id> = self
            .sources
            .iter()
            .filter(|(_, s)| self.budget.expired(s.touched, now))
            .map(|(k, _)| *k)
            .collect();
        for k in old {
            let n = self.remove(k);
            self.stats.timed_out += n.max(1) as u64;
        }
    }

    /// Drops everything `src` holds; returns how many messages were in progress.
    fn remove(&mut self, src: As4Id) -> usize {
        let Some(s) = self.sources.remove(&src) else {
            return 0;
        };
        self.budget.release(src, s.bytes);
        self.in_progress -= s.streams.len();
        s.streams.len()
    }

    /// Drops the stream of `src` whose first packet has sequence number `f`.
    fn drop_stream(&mut self, src: As4Id, f: u16) {
        let Some(s) = self.sources.get_mut(&src) else {
            return;
        };
        let Some(st) = s.streams.remove(&f) else {
            return;
        };
        let bytes: usize = st.parts.values().map(|p| cost(p)).sum();
        s.bytes -= bytes;
        s.payload -= st.parts.values().map(Vec::len).sum::<usize>();
        self.in_progress -= 1;
        self.budget.release(src, bytes);
    }

    /// The whole message a packet brings: a single packet as it is, a packet of a large
    /// message once it completes the message ([`push`](Self::push)).
    pub fn message(&mut self, now: Instant, packet: As4Packet) -> Option<As4Packet> {
        if packet.header.data_control == DataControl::Single {
            Some(packet)
        } else {
            self.push(now, packet)
        }
    }

    /// Takes one packet of a large message; returns the rebuilt message (a single
    /// packet: the first packet's header, the whole payload, the first's sequence
    /// number) when it is complete.
    pub fn push(&mut self, now: Instant, packet: As4Packet) -> Option<As4Packet> {
        let dc = packet.header.data_control;
        if dc == DataControl::Single || packet.header.ack_nak.is_answer() {
            self.stats.orphans += 1;
            return None;
        }
        let src = packet.header.source;
        let seq = packet.sequence;
        if dc == DataControl::First {
            let same = self
                .sources
                .get(&src)
                .and_then(|s| s.streams.get(&seq))
                .and_then(|st| st.parts.get(&0))
                .map(|p| *p == packet.payload);
            match same {
                Some(true) => {
                    self.stats.duplicates += 1;
                    if let Some(s) = self.sources.get_mut(&src) {
                        s.touched = now;
                    }
                    return None;
                }
                Some(false) => {
                    self.drop_stream(src, seq);
                    self.stats.restarted += 1;
                }
                None => {}
            }
            if self.in_progress >= self.max_in_progress {
                self.stats.over_limit += 1;
                return None;
            }
        }
        // What the packet replaces, and the bytes it adds.
        let held = self
            .sources
            .get(&src)
            .and_then(|s| s.held(seq, s.slot(seq, dc)));
        if let Some(old) = &held {
            if *old == (dc, packet.payload.as_slice()) {
                self.stats.duplicates += 1;
                if let Some(s) = self.sources.get_mut(&src) {
                    s.touched = now;
                }
                return None;
            }
            self.stats.restarted += 1;
        }
        let before = held.map_or(0, |(_, p)| cost(p));
        let delta = cost(&packet.payload) as isize - before as isize;
        let delta_payload = delta - if held.is_some() { 0 } else { OVERHEAD as isize };
        let payload = self.sources.get(&src).map_or(0, |s| s.payload);
        if delta > 0
            && !self
                .budget
                .admits(src, payload, delta_payload.max(0) as usize, delta as usize)
        {
            self.stats.over_limit += 1;
            self.remove(src);
            return None;
        }
        self.budget.adjust(src, delta);
        let s = self.sources.entry(src).or_insert_with(|| Source {
            streams: BTreeMap::new(),
            early: BTreeMap::new(),
            bytes: 0,
            payload: 0,
            touched: now,
        });
        s.bytes = (s.bytes as isize + delta) as usize;
        s.payload = (s.payload as isize + delta_payload) as usize;
        s.touched = now;
        let streams_before = s.streams.len();
        let (first, freed) = s.file(packet);
        s.bytes -= freed;
        s.payload -= freed.saturating_sub(OVERHEAD);
        self.budget.release(src, freed);
        self.in_progress = self.in_progress + s.streams.len() - streams_before;
        let f = first?;
        let done = s.complete(f)?;
        self.in_progress -= 1;
        let bytes: usize = done.parts.values().map(|p| cost(p)).sum();
        s.bytes -= bytes;
        s.payload -= done.parts.values().map(Vec::len).sum::<usize>();
        let empty = s.streams.is_empty() && s.early.is_empty();
        self.budget.release(src, bytes);
        if empty {
            // Nothing is held: its count is zero too.
            self.remove(src);
        }
        self.stats.completed += 1;
        let mut payload = Vec::with_capacity(bytes);
        for p in done.parts.values() {
            payload.extend_from_slice(p);
        }
        Some(As4Packet {
            header: As4Header {
                data_control: DataControl::Single,
                ..done.header
            },
            payload,
            sequence: f,
        })
    }
}

impl Source {
    /// The stream a non-first packet at `seq` belongs to: the nearest first packet at or
    /// before it (wrapping), if the packet is within that stream's known end; with the
    /// packet's offset in it.
    fn stream_of(&self, seq: u16) -> Option<(u16, u16)> {
        let (&f, st) = self
            .streams
            .range(..=seq)
            .next_back()
            .or_else(|| self.streams.iter().next_back())?;
        let off = seq.wrapping_sub(f);
        (off > 0 && st.last.is_none_or(|l| off <= l)).then_some((f, off))
    }

    /// Where a packet at `seq` flagged `dc` is filed.
    fn slot(&self, seq: u16, dc: DataControl) -> Slot {
        if dc == DataControl::First {
            return Slot::First;
        }
        match self.stream_of(seq) {
            Some((f, off))
                if dc == DataControl::Normal || self.streams[&f].last.is_none_or(|l| l == off) =>
            {
                Slot::Stream(f, off)
            }
            _ => Slot::Early,
        }
    }

    /// The packet held where a packet at `seq` goes (`slot`): its flag and payload.
    fn held(&self, seq: u16, slot: Slot) -> Option<(DataControl, &[u8])> {
        let early = || {
            self.early
                .get(&seq)
                .map(|e| (e.data_control, e.payload.as_slice()))
        };
        match slot {
            Slot::First => self
                .streams
                .get(&seq)
                .and_then(|st| st.parts.get(&0))
                .map(|p| (DataControl::First, p.as_slice()))
                .or_else(early),
            Slot::Stream(f, off) => {
                let st = self.streams.get(&f)?;
                let flag = if st.last == Some(off) {
                    DataControl::Last
                } else {
                    DataControl::Normal
                };
                st.parts
                    .get(&off)
                    .map(|p| (flag, p.as_slice()))
                    .or_else(early)
            }
            Slot::Early => early(),
        }
    }

    /// Files `p` (its bytes already counted, replacing what [`held`](Self::held)
    /// found); returns the first sequence number of the stream it joined, if any, and
    /// the bytes of packets it displaced.
    fn file(&mut self, p: As4Packet) -> (Option<u16>, usize) {
        let seq = p.sequence;
        let dc = p.header.data_control;
        let slot = self.slot(seq, dc);
        if slot != Slot::Early {
            self.early.remove(&seq);
        }
        match slot {
            Slot::First => {
                let mut parts = BTreeMap::new();
                parts.insert(0, p.payload);
                let st = Stream {
                    header: p.header,
                    parts,
                    last: None,
                };
                self.streams.insert(seq, st);
                let freed = self.adopt(seq);
                self.claim(seq, 1);
                (Some(seq), freed)
            }
            Slot::Early => {
                let early = Early {
                    data_control: dc,
                    payload: p.payload,
                };
                self.early.insert(seq, early);
                (None, 0)
            }
            Slot::Stream(f, off) => {
                let Some(st) = self.streams.get_mut(&f) else {
                    return (None, 0);
                };
                st.parts.insert(off, p.payload);
                if dc == DataControl::Last {
                    st.last = Some(off);
                    // Packets filed beyond the end belong to a later message.
                    let beyond = off
                        .checked_add(1)
                        .map(|next| st.parts.split_off(&next))
                        .unwrap_or_default();
                    for (o, payload) in beyond {
                        let early = Early {
                            data_control: DataControl::Normal,
                            payload,
                        };
                        self.early.insert(f.wrapping_add(o), early);
                    }
                }
                self.claim(f, off.wrapping_add(1));
                (Some(f), 0)
            }
        }
    }

    /// A stream was opened at `f`: the packets the stream before it (whose end is not
    /// known) holds from `f` on are nearer to `f`, and move to it. Returns the bytes of
    /// a packet held at `f` itself, which the new first packet displaces.
    fn adopt(&mut self, f: u16) -> usize {
        let prev = self
            .streams
            .range(..f)
            .next_back()
            .or_else(|| self.streams.range(f.wrapping_add(1)..).next_back())
            .map(|(&p, st)| (p, st.last));
        let Some((prev, None)) = prev else {
            return 0;
        };
        let d = f.wrapping_sub(prev);
        let moved = match self.streams.get_mut(&prev) {
            Some(st) if d > 0 => st.parts.split_off(&d),
            _ => return 0,
        };
        let mut freed = 0;
        let mut offsets = Vec::with_capacity(moved.len());
        if let Some(st) = self.streams.get_mut(&f) {
            for (o, payload) in moved {
                if o == d {
                    freed += cost(&payload);
                } else {
                    st.parts.insert(o - d, payload);
                    offsets.push(o - d);
                }
            }
        }
        for o in offsets {
            self.claim(f, o.wrapping_add(1));
        }
        freed
    }

    /// Moves the early packets that follow offset `from` of stream `f` into it, up to
    /// the first gap or the stream's last packet.
    fn claim(&mut self, f: u16, from: u16) {
        let Some(st) = self.streams.get_mut(&f) else {
            return;
        };
        let mut off = from;
        while off != 0 && st.last.is_none_or(|l| off <= l) && !st.parts.contains_key(&off) {
            let seq = f.wrapping_add(off);
            // Only normal and last packets wait in `early`.
            let Some(e) = self.early.remove(&seq) else {
                return;
            };
            st.parts.insert(off, e.payload);
            if e.data_control == DataControl::Last {
                st.last = Some(off);
                return;
            }
            off = off.wrapping_add(1);
        }
    }

    /// Takes stream `f` out when it is complete: its last packet and every one before.
    fn complete(&mut self, f: u16) -> Option<Stream> {
        let st = self.streams.get(&f)?;
        let last = st.last?;
        if st.parts.len() != usize::from(last) + 1 {
            return None;
        }
        self.streams.remove(&f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn packet(dc: DataControl, seq: u16) -> As4Packet {
        As4Packet {
            header: As4Header {
                data_control: dc,
                ..As4Header::new(As4Id::new(1, 1, 1), As4Id::new(2, 1, 1))
            },
            payload: vec![seq as u8; 3],
            sequence: seq,
        }
    }

    #[test]
    fn a_last_packet_just_before_a_first_is_held_without_overflow() {
        // The last packet at 0 is 65,535 after the first at 1 (the case proptest found).
        let t = Instant::now();
        let mut r = As4Reassembler::new(As4ReassemblyLimits::default());
        assert!(r.push(t, packet(DataControl::First, 1)).is_none());
        assert!(r.push(t, packet(DataControl::Last, 0)).is_none());
        assert!(r.push(t, packet(DataControl::Normal, 0)).is_none());
        assert_eq!(r.in_progress(), 1);
        r.expire(t + std::time::Duration::from_secs(2));
        assert_eq!((r.buffered(), r.in_progress()), (0, 0));
    }

    #[test]
    fn a_first_packet_with_other_bytes_restarts_its_message() {
        let t = Instant::now();
        let mut r = As4Reassembler::new(As4ReassemblyLimits::default());
        r.push(t, packet(DataControl::First, 5));
        r.push(t, packet(DataControl::Normal, 6));
        let mut again = packet(DataControl::First, 5);
        again.payload = vec![9, 9];
        r.push(t, again);
        assert_eq!(r.stats().restarted, 1);
        let whole = r.push(t, packet(DataControl::Last, 6)).expect("whole");
        assert_eq!(whole.payload, [9, 9, 6, 6, 6]);
        assert_eq!((r.buffered(), r.in_progress()), (0, 0));
    }
}
