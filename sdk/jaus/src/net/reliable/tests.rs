//! Tests of the sender and the receiver.

use super::*;

fn sender() -> Sender<u16, u8, &'static str> {
    Sender::new(RetryPolicy::default())
}

#[test]
fn cautiously_a_peer_not_yet_known_gets_one_copy_then_resends_once_it_acknowledged() {
    // Cautious: a peer that never acknowledged gets one copy of each message (a
    // peer that neither acknowledges nor drops copies carries out each once).
    let t0 = Instant::now();
    let mut s: Sender<u16, u8, &'static str> = Sender::new(RetryPolicy::cautious());
    assert_eq!(s.track(t0, 1, 4, "waypoint"), Tracked::Send);
    let mut copies = Vec::new();
    while let Some(next) = s.next_timeout() {
        s.poll(next, |k, _| copies.push((next - t0, *k)));
    }
    assert!(copies.is_empty(), "no second copy: {copies:?}");
    let d = s.poll_delivery().unwrap();
    assert_eq!((d.outcome, d.attempts), (Outcome::GaveUp, 1));
    assert_eq!(d.elapsed, RetryPolicy::cautious().hold_unknown);
    // Once it acknowledged something, its messages are resent until acknowledged.
    let t1 = t0 + Duration::from_secs(10);
    assert_eq!(s.track(t1, 2, 4, "speed"), Tracked::Send);
    assert!(s.answered(t1, 2, 4, true, |_| false));
    assert_eq!(s.track(t1, 3, 4, "resume"), Tracked::Send);
    let mut again = 0;
    while let Some(next) = s.next_timeout() {
        s.poll(next, |_, _| again += 1);
    }
    assert_eq!(again, 5, "five more copies to a peer known to acknowledge");
}

#[test]
fn the_wait_doubles_up_to_its_bound() {
    let p = RetryPolicy::default();
    let waits: Vec<u64> = (1..=6)
        .map(|a| p.wait_after(a).as_millis() as u64)
        .collect();
    assert_eq!(waits, [200, 400, 800, 1600, 1600, 1600]);
    assert_eq!(p.wait_after(u32::MAX), p.max_timeout);
}

#[test]
fn an_unanswered_message_is_resent_with_backoff_then_given_up() {
    let t0 = Instant::now();
    let mut s = sender();
    assert_eq!(s.track(t0, 7, 1, "resume"), Tracked::Send);
    let mut copies = Vec::new();
    let mut t = t0;
    while let Some(next) = s.next_timeout() {
        t = next;
        s.poll(t, |k, m| copies.push((t - t0, *k, *m)));
    }
    let at: Vec<u128> = copies.iter().map(|c| c.0.as_millis()).collect();
    assert_eq!(
        at,
        [200, 600, 1400, 3000, 4600],
        "five copies after the first"
    );
    let d = s.poll_delivery().unwrap();
    assert_eq!((d.key, d.outcome, d.attempts), (7, Outcome::GaveUp, 6));
    assert_eq!(d.elapsed, t - t0);
    let st = s.stats();
    assert_eq!((st.tracked, st.retried, st.given_up), (1, 5, 1));
}

#[test]
fn an_acknowledgement_settles_its_message_only() {
    let t0 = Instant::now();
    let mut s = sender();
    assert_eq!(s.track(t0, 1, 9, "a"), Tracked::Send);
    assert_eq!(
        s.track(t0, 2, 9, "b"),
        Tracked::Held,
        "one at a time per peer"
    );
    assert!(
        !s.answered(t0, 2, 9, true, |_| false),
        "a held one is not answered"
    );
    assert!(s.answered(t0, 1, 9, true, |_| false));
    assert!(
        !s.answered(t0, 1, 9, true, |_| false),
        "a second ACK is stray"
    );
    let later = t0 + Duration::from_millis(250);
    s.poll(later, |_, _| {});
    assert!(s.answered(later, 2, 9, true, |_| false));
    assert_eq!(s.poll_delivery().unwrap().key, 1);
    let d = s.poll_delivery().unwrap();
    assert_eq!(
        (d.key, d.outcome, d.attempts),
        (2, Outcome::Acknowledged, 1)
    );
    // A NAK without the key settles the oldest the matcher accepts.
    assert_eq!(s.track(later, 3, 9, "c"), Tracked::Send);
    assert!(s.answered(later, 99, 9, false, |k| *k == 3));
    assert_eq!(s.poll_delivery().unwrap().outcome, Outcome::Refused);
    assert_eq!(s.waiting(), 0);
    assert_eq!(s.stats().stray_answers, 2);
}

#[test]
fn a_peer_that_never_acknowledges_is_no_longer_asked() {
    let t0 = Instant::now();
    let mut s = sender();
    assert_eq!(s.track(t0, 0, 5, "x"), Tracked::Send);
    assert_eq!(s.track(t0, 1, 5, "x"), Tracked::Held);
    let mut t = t0;
    while let Some(next) = s.next_timeout() {
        t = next;
        s.poll(t, |_, _| {});
    }
    assert_eq!(
        s.stats().given_up,
        2,
        "the held one went 2 s after the first"
    );
    assert!(!s.acknowledges(5));
    assert_eq!(s.track(t, 3, 5, "y"), Tracked::Untracked, "sent once");
    assert_eq!(s.stats().untracked_peer, 1);
    // A peer that acknowledged once stays asked, however many go unanswered.
    assert_eq!(s.track(t, 10, 6, "z"), Tracked::Send);
    assert!(s.answered(t, 10, 6, true, |_| false));
    for k in 11..15 {
        assert_ne!(s.track(t, k, 6, "z"), Tracked::Untracked);
    }
    while let Some(next) = s.next_timeout() {
        t = next;
        s.poll(t, |_, _| {});
    }
    assert_eq!(s.stats().given_up, 6);
    assert!(s.acknowledges(6));
}

#[test]
fn the_waiting_messages_are_bounded() {
    let t0 = Instant::now();
    let mut s: Sender<u32, u8, ()> = Sender::new(RetryPolicy {
        max_outstanding: 3,
        ..RetryPolicy::default()
    });
    let tracked = (0..5)
        .filter(|k| s.track(t0, *k, 1, ()) != Tracked::Untracked)
        .count();
    assert_eq!(tracked, 3);
    assert_eq!(s.stats().untracked_full, 2);
}

#[test]
fn behind_a_peer_not_yet_known_to_answer_a_message_waits_a_little_only() {
    let t0 = Instant::now();
    let mut s = sender();
    assert_eq!(s.track(t0, 1, 3, "a"), Tracked::Send);
    assert_eq!(s.track(t0, 2, 3, "b"), Tracked::Held);
    let mut sent = Vec::new();
    s.poll(t0 + Duration::from_millis(200), |k, _| sent.push(*k));
    assert_eq!(sent, [1], "the first again, the second still held");
    s.poll(t0 + Duration::from_millis(600), |k, _| sent.push(*k));
    s.poll(t0 + Duration::from_millis(1400), |k, _| sent.push(*k));
    assert_eq!(sent, [1, 1, 1], "the first's copies, the second still held");
    s.poll(t0 + Duration::from_secs(2), |k, _| sent.push(*k));
    assert_eq!(sent, [1, 1, 1, 2], "the second after 2 s");
    // Answered within the hold, the next goes at once.
    assert_eq!(s.track(t0, 3, 7, "c"), Tracked::Send);
    assert_eq!(s.track(t0, 4, 7, "d"), Tracked::Held);
    let t = t0 + Duration::from_millis(30);
    assert!(s.answered(t, 3, 7, true, |_| false));
    assert_eq!(s.next_timeout(), Some(t));
}

#[test]
fn messages_held_behind_a_peer_not_yet_known_go_one_hold_apart() {
    let t0 = Instant::now();
    let mut s = sender();
    assert_eq!(s.track(t0, 1, 3, "control"), Tracked::Send);
    for k in 2..=4 {
        assert_eq!(s.track(t0, k, 3, "batch"), Tracked::Held);
    }
    let mut firsts = Vec::new();
    let mut seen = std::collections::HashSet::from([1]);
    while let Some(next) = s.next_timeout() {
        if next > t0 + Duration::from_secs(7) {
            break;
        }
        s.poll(next, |k, _| {
            if seen.insert(*k) {
                firsts.push(((next - t0).as_millis(), *k));
            }
        });
    }
    // Each held one goes a hold after the one before it, in order.
    assert_eq!(firsts, [(2000, 2), (4000, 3), (6000, 4)]);
    // Cautiously, a peer learnt never to answer gets what was held at once.
    let mut s: Sender<u16, u8, &'static str> = Sender::new(RetryPolicy::cautious());
    for k in 1..=5 {
        s.track(t0, k, 3, "waypoint");
    }
    let mut sent = Vec::new();
    while let Some(next) = s.next_timeout() {
        s.poll(next, |k, _| sent.push(((next - t0).as_millis(), *k)));
    }
    assert_eq!(sent, [(2000, 2), (4000, 3), (4000, 4), (4000, 5)]);
    assert!(!s.acknowledges(3));
}

#[test]
fn a_peer_known_to_answer_gets_its_messages_in_order() {
    let t0 = Instant::now();
    let mut s = sender();
    assert_eq!(s.track(t0, 1, 4, "control"), Tracked::Send);
    assert!(s.answered(t0, 1, 4, true, |_| false));
    // Now known: the second and third wait behind the first.
    assert_eq!(s.track(t0, 2, 4, "resume"), Tracked::Send);
    assert_eq!(s.track(t0, 3, 4, "speed"), Tracked::Held);
    assert_eq!(s.track(t0, 4, 4, "waypoint"), Tracked::Held);
    assert_eq!(s.track(t0, 5, 8, "other peer"), Tracked::Send);
    let mut sent = Vec::new();
    // Resume is lost: only it goes again, the others stay held.
    let t1 = t0 + Duration::from_millis(200);
    s.poll(t1, |k, _| sent.push(*k));
    assert_eq!(sent, [2, 5]);
    // Its answer releases the next, and that one's the last.
    assert!(s.answered(t1, 2, 4, true, |_| false));
    assert_eq!(s.next_timeout(), Some(t1));
    s.poll(t1, |k, _| sent.push(*k));
    assert_eq!(sent, [2, 5, 3]);
    assert!(s.answered(t1, 3, 4, true, |_| false));
    s.poll(t1, |k, _| sent.push(*k));
    assert_eq!(sent, [2, 5, 3, 4]);
    // A held message is not answered by a stray ACK of its key.
    assert_eq!(s.stats().retried, 2);
}

#[test]
fn a_retransmission_is_carried_out_once_and_answered_again() {
    let t0 = Instant::now();
    let mut r: Receiver<(u8, u16), &str> = Receiver::new(&RetryPolicy::default());
    assert_eq!(r.arrived(t0, (1, 5)), Arrival::New);
    // Before the answer: dropped, nothing to repeat.
    assert_eq!(r.arrived(t0, (1, 5)), Arrival::Duplicate(None));
    r.answered((1, 5), "ack");
    assert_eq!(r.arrived(t0, (1, 5)), Arrival::Duplicate(Some("ack")));
    assert_eq!(r.arrived(t0, (2, 5)), Arrival::New, "another sender");
    // After the window it is new again.
    let later = t0 + Duration::from_secs(11);
    assert_eq!(r.arrived(later, (1, 5)), Arrival::New);
    let mut st = ReliableStats::default();
    r.add_stats(&mut st);
    assert_eq!((st.duplicates_dropped, st.answers_repeated), (2, 1));
}

#[test]
fn the_remembered_receptions_are_bounded() {
    let t0 = Instant::now();
    let mut r: Receiver<u32, ()> = Receiver::new(&RetryPolicy {
        max_remembered: 10,
        ..RetryPolicy::default()
    });
    for k in 0..100 {
        assert_eq!(r.arrived(t0, k), Arrival::New);
    }
    assert!(!r.remembers(&0) && r.remembers(&99));
    assert!(r.seen.len() <= 10 && r.order.len() <= 10);
}
