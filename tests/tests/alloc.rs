//! Decoding and encoding a fixed-size message makes no heap allocation.
//!
//! A counting global allocator wraps the system allocator; the counter is per thread
//! so that the test harness's own threads do not disturb it.

use jaus::codec::{Decode, Encode, Writer};
use jaus::messages::{ReportGlobalPose, SetGlobalPathSegment, SetWrenchEffort};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: every method forwards to `System` with the caller's arguments unchanged, so
// `System`'s guarantees hold; the only addition is a thread-local counter update, which
// neither allocates (const-initialised `Cell`) nor touches the memory handed out.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        // SAFETY: forwarded unchanged; the caller upholds `alloc`'s contract.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System.alloc` with this `layout` (via `alloc` above).
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        // SAFETY: forwarded unchanged; `ptr`/`layout` come from this allocator.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCS.with(Cell::get);
    f();
    ALLOCS.with(Cell::get) - before
}

fn body(hex: &str) -> Vec<u8> {
    jaus::hex::decode(hex).unwrap()[16..].to_vec()
}

#[test]
fn fixed_size_messages_decode_and_encode_without_allocating() {
    let pose = body(jaus::json::REFERENCE_PACKETS[0].1);
    let wrench = body(jaus::json::REFERENCE_PACKETS[1].1);
    let segment = body(jaus::json::REFERENCE_PACKETS[2].1);
    let mut out = [0u8; 64];

    let n = allocations(|| {
        for _ in 0..100 {
            let p = ReportGlobalPose::from_bytes(std::hint::black_box(&pose)).unwrap();
            let w = SetWrenchEffort::from_bytes(std::hint::black_box(&wrench)).unwrap();
            let s = SetGlobalPathSegment::from_bytes(std::hint::black_box(&segment)).unwrap();
            p.encode(&mut Writer::new(&mut out)).unwrap();
            w.encode(&mut Writer::new(&mut out)).unwrap();
            s.encode(&mut Writer::new(&mut out)).unwrap();
            std::hint::black_box((&p, &w, &s, &out));
        }
    });
    assert_eq!(
        n, 0,
        "decoding/encoding fixed-size messages allocated {n} time(s)"
    );

    // The counter does count: a Vec allocates.
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 10]))) > 0);
}

mod route {
    //! receive → route → deliver → reply through a sans-IO `Node`, for a fixed-size
    //! query and its report.

    use super::allocations;
    use jaus::component::{Config, Refused};
    use jaus::components::global_pose_sensor::{self, Ctx, GlobalPoseSensor};
    use jaus::messages::{QueryGlobalPose, ReportGlobalPose};
    use jaus::net::{Framing, Node, NodeConfig};
    use jaus::{Address, Header, JausMessage};
    use std::net::SocketAddr;
    use std::time::{Duration, Instant};

    const GPS: Address = Address::new(1, 1, 38, 1);
    const OCU: Address = Address::new(2, 1, 40, 1);

    struct Gps;
    impl GlobalPoseSensor for Gps {
        fn on_query_global_pose(
            &mut self,
            _c: &mut Ctx<'_>,
            _q: &QueryGlobalPose,
        ) -> Result<ReportGlobalPose, Refused> {
            Ok(ReportGlobalPose {
                latitude: Some(29.6),
                longitude: Some(-82.3),
                yaw: Some(0.5),
                ..Default::default()
            })
        }
    }

    #[test]
    fn a_routed_query_and_its_report_allocate_nothing() {
        let t0 = Instant::now();
        let peer: SocketAddr = "127.0.0.1:4000".parse().unwrap();
        let mut node = Node::new(
            NodeConfig {
                subsystem: 1,
                node: 1,
                peers: vec![peer],
                ..NodeConfig::default()
            },
            t0,
        );
        node.add(global_pose_sensor::component(
            GPS,
            Gps,
            Config::default(),
            t0,
        ))
        .unwrap();
        let mut packet = vec![0u8; 64];
        let n = Header::new(QueryGlobalPose::CODE, GPS, OCU)
            .write_packet(
                &QueryGlobalPose {
                    presence_vector: 0x1FF,
                },
                &mut packet,
            )
            .unwrap();
        packet.truncate(n);
        let datagram = Framing::Judp.encode(&packet);
        let mut now = t0;
        let mut replies = 0usize;
        let round = |node: &mut Node, now: Instant, replies: &mut usize| {
            node.handle_datagram(now, peer, &datagram);
            while let Some(d) = node.poll_transmit() {
                if let Ok(p) = Framing::Judp.packet(&d.bytes) {
                    if p.0.command_code == ReportGlobalPose::CODE {
                        *replies += 1;
                    }
                }
                node.recycle(d.bytes);
            }
        };
        // Warm up: the node learns the peer, queues and pools reach their sizes.
        for _ in 0..200 {
            now += Duration::from_micros(100);
            round(&mut node, now, &mut replies);
        }
        let before = replies;
        let n = allocations(|| {
            for _ in 0..1_000 {
                now += Duration::from_micros(100);
                round(&mut node, now, &mut replies);
            }
        });
        assert_eq!(replies - before, 1_000, "every query answered");
        assert_eq!(
            n, 0,
            "1,000 routed query/report pairs allocated {n} time(s)"
        );
    }
}
