//! The List Manager of the Core runtime.

mod core_common;

use std::time::Instant;

use core_common::*;
use jaus::JausMessage;
use jaus_as4::component::As4Component;
use jaus_as4::core::lists::Lists;
use jaus_as4::core::CoreConfig;
use jaus_as4::{
    ConfirmElementRequest, DeleteElement, Element, ElementFormat, ElementRejection, Message,
    QueryElement, QueryElementCount, QueryElementList, RejectElementRequest, ReportElement,
    ReportElementCount, ReportElementList, RequestControl, SetElement, SetLocalWaypoint,
    SetTravelSpeed,
};

fn waypoint(uid: u16, prev: u16, next: u16) -> Element {
    let wp = SetLocalWaypoint {
        x: f64::from(uid),
        ..Default::default()
    };
    Element::holding(uid, prev, next, &wp.into()).unwrap()
}

fn set(c: &mut As4Component<()>, request_id: u8, elements: Vec<Element>) -> Message {
    let t = Instant::now();
    only_for(
        &send(
            c,
            t,
            A,
            SetElement {
                request_id,
                elements,
            },
        ),
        A,
    )
}

fn rejected(request_id: u8, response_code: ElementRejection) -> Message {
    RejectElementRequest {
        request_id,
        response_code,
    }
    .into()
}

fn order(c: &mut As4Component<()>) -> Vec<u16> {
    match only_for(&send(c, Instant::now(), B, QueryElementList {}), B) {
        Message::ReportElementList(ReportElementList { element_uids }) => element_uids,
        m => panic!("{m:?}"),
    }
}

fn controlled() -> As4Component<()> {
    let (mut c, _) = component(CoreConfig::named("rover"));
    send(
        &mut c,
        Instant::now(),
        A,
        RequestControl { authority_code: 0 },
    );
    c
}

#[test]
fn insert_at_tail_head_and_middle() {
    let mut c = controlled();
    // A whole list in one request, forward references included.
    let ok = set(
        &mut c,
        1,
        vec![
            waypoint(10, 0, 20),
            waypoint(20, 10, 30),
            waypoint(30, 20, 0),
        ],
    );
    assert_eq!(ok, ConfirmElementRequest { request_id: 1 }.into());
    assert_eq!(order(&mut c), vec![10, 20, 30]);
    // Tail.
    set(&mut c, 2, vec![waypoint(40, 30, 0)]);
    // Head.
    set(&mut c, 3, vec![waypoint(5, 0, 10)]);
    // Middle.
    assert_eq!(
        set(&mut c, 4, vec![waypoint(25, 20, 30)]),
        ConfirmElementRequest { request_id: 4 }.into()
    );
    assert_eq!(order(&mut c), vec![5, 10, 20, 25, 30, 40]);
    let lists = c.core().lists();
    assert_eq!(lists.head(), Some(5));
    assert_eq!(
        lists.get(25).map(|e| (e.previous_uid, e.next_uid)),
        Some((20, 30))
    );
    assert_eq!(
        lists.iter_from(25).map(|e| e.uid).collect::<Vec<_>>(),
        vec![25, 30, 40]
    );
    // Replacing an element's data in place.
    let mut moved = waypoint(25, 20, 30);
    moved.data = Element::holding(
        25,
        20,
        30,
        &SetLocalWaypoint {
            x: 99.0,
            ..Default::default()
        }
        .into(),
    )
    .unwrap()
    .data;
    set(&mut c, 5, vec![moved.clone()]);
    assert_eq!(
        only_for(
            &send(&mut c, Instant::now(), B, QueryElement { element_uid: 25 }),
            B
        ),
        ReportElement { element: moved }.into()
    );
    assert_eq!(
        only_for(&send(&mut c, Instant::now(), B, QueryElementCount {}), B),
        ReportElementCount { element_count: 6 }.into()
    );
}

#[test]
fn bad_links_are_rejected_with_the_right_code() {
    let mut c = controlled();
    set(
        &mut c,
        1,
        vec![waypoint(1, 0, 2), waypoint(2, 1, 3), waypoint(3, 2, 0)],
    );
    let revision = c.core().lists().revision();
    // Previous that does not exist.
    assert_eq!(
        set(&mut c, 2, vec![waypoint(9, 7, 0)]),
        rejected(2, ElementRejection::InvalidPreviousElement)
    );
    // Next that does not exist.
    assert_eq!(
        set(&mut c, 3, vec![waypoint(9, 3, 8)]),
        rejected(3, ElementRejection::InvalidNextElement)
    );
    // Previous and next that are not neighbours.
    assert_ne!(
        set(&mut c, 4, vec![waypoint(9, 1, 3)]),
        ConfirmElementRequest { request_id: 4 }.into()
    );
    // A second head.
    assert_ne!(
        set(&mut c, 5, vec![waypoint(9, 0, 0)]),
        ConfirmElementRequest { request_id: 5 }.into()
    );
    // Linking to itself; UID 0 and 65535.
    assert_eq!(
        set(&mut c, 6, vec![waypoint(9, 9, 0)]),
        rejected(6, ElementRejection::InvalidPreviousElement)
    );
    assert_eq!(
        set(&mut c, 7, vec![waypoint(0, 3, 0)]),
        rejected(7, ElementRejection::InvalidElementId)
    );
    assert_eq!(
        set(&mut c, 8, vec![waypoint(0xFFFF, 3, 0)]),
        rejected(8, ElementRejection::InvalidElementId)
    );
    // Data that is not a message; a user-defined format.
    let mut junk = waypoint(9, 3, 0);
    junk.data = vec![1];
    assert_eq!(
        set(&mut c, 9, vec![junk]),
        rejected(9, ElementRejection::UnsupportedElementType)
    );
    let mut user = waypoint(9, 3, 0);
    user.format = ElementFormat::UserDefined;
    assert_eq!(
        set(&mut c, 10, vec![user]),
        rejected(10, ElementRejection::UnsupportedElementType)
    );
    // Nothing of it changed the list.
    assert_eq!(c.core().lists().revision(), revision);
    assert_eq!(order(&mut c), vec![1, 2, 3]);
}

#[test]
fn supported_types_and_the_bound() {
    let mut lists = Lists::new(2);
    lists.support(SetLocalWaypoint::CODE);
    let speed = Element::holding(1, 0, 0, &SetTravelSpeed { speed: 1.0 }.into()).unwrap();
    assert_eq!(
        lists.set(&[speed]),
        Err(ElementRejection::UnsupportedElementType)
    );
    assert_eq!(lists.set(&[waypoint(1, 0, 2), waypoint(2, 1, 0)]), Ok(()));
    assert_eq!(
        lists.set(&[waypoint(3, 2, 0)]),
        Err(ElementRejection::OutOfMemory)
    );
    assert_eq!(lists.uids(), vec![1, 2]);
}

#[test]
fn circular_list() {
    let mut lists = Lists::new(16);
    lists
        .set(&[waypoint(1, 0, 2), waypoint(2, 1, 3), waypoint(3, 2, 1)])
        .unwrap();
    assert_eq!(lists.uids(), vec![1, 2, 3]);
    assert_eq!(
        lists.iter_from(2).map(|e| e.uid).collect::<Vec<_>>(),
        vec![2, 3, 1]
    );
    // Deleting the head keeps the circle closed on the new head.
    lists.delete(&[1]).unwrap();
    assert_eq!(lists.uids(), vec![2, 3]);
    assert_eq!(lists.get(3).unwrap().next_uid, 2);
}

#[test]
fn delete_relinks_and_needs_control() {
    let mut c = controlled();
    set(
        &mut c,
        1,
        vec![
            waypoint(1, 0, 2),
            waypoint(2, 1, 3),
            waypoint(3, 2, 4),
            waypoint(4, 3, 0),
        ],
    );
    let t = Instant::now();
    // From a client without control: ignored, counted.
    assert!(send(
        &mut c,
        t,
        B,
        DeleteElement {
            request_id: 2,
            element_uids: vec![2]
        }
    )
    .is_empty());
    assert_eq!(c.stats().not_controller, 1);
    assert!(send(
        &mut c,
        t,
        B,
        SetElement {
            request_id: 2,
            elements: vec![waypoint(5, 4, 0)]
        }
    )
    .is_empty());
    assert_eq!(c.stats().not_controller, 2);
    // Middle, then head.
    let out = send(
        &mut c,
        t,
        A,
        DeleteElement {
            request_id: 3,
            element_uids: vec![2],
        },
    );
    assert_eq!(
        only_for(&out, A),
        ConfirmElementRequest { request_id: 3 }.into()
    );
    assert_eq!(order(&mut c), vec![1, 3, 4]);
    assert_eq!(c.core().lists().get(3).unwrap().previous_uid, 1);
    send(
        &mut c,
        t,
        A,
        DeleteElement {
            request_id: 4,
            element_uids: vec![1],
        },
    );
    assert_eq!(order(&mut c), vec![3, 4]);
    // An unknown UID: rejected, nothing removed.
    let out = send(
        &mut c,
        t,
        A,
        DeleteElement {
            request_id: 5,
            element_uids: vec![4, 77],
        },
    );
    assert_eq!(
        only_for(&out, A),
        rejected(5, ElementRejection::ElementIdNotFound)
    );
    assert_eq!(order(&mut c), vec![3, 4]);
    // Query Element of an unknown UID is not answered.
    assert!(send(&mut c, t, B, QueryElement { element_uid: 77 }).is_empty());
    // 65535: every element.
    send(
        &mut c,
        t,
        A,
        DeleteElement {
            request_id: 6,
            element_uids: vec![0xFFFF],
        },
    );
    assert_eq!(
        only_for(&send(&mut c, t, B, QueryElementCount {}), B),
        ReportElementCount { element_count: 0 }.into()
    );
}
