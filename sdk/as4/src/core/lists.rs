//! The List Manager (`urn:jaus:jss:core:ListManager` 1.1): one ordered list of elements
//! per component, linked by UID like a doubly linked list.
//!
//! Each [`Element`] names the UID of the element before it (`previous_uid`, 0 at the
//! head) and after it (`next_uid`, 0 at the tail; the head's UID when the list is
//! circular). A list is valid when it has exactly one head, every link names an element
//! of the list (or 0), the links agree both ways (`a.next = b` exactly when
//! `b.previous = a`, the closing link of a circular list excepted), no element links to
//! itself, and walking from the head reaches every element.
//!
//! [Set Element](SetElement) stores its elements as one transaction: each element is
//! written (replacing one of the same UID), the neighbours it names are re-linked to it
//! (so that inserting at the head, in the middle or at the tail needs only the new
//! element), and the result must be a valid list; otherwise nothing changes and the
//! answer is a [Reject Element Request](RejectElementRequest). Elements may name
//! elements that come later in the same request, so a whole list can be sent at once.
//! Moving an existing element to another place is a Delete Element and a Set Element.
//!
//! Who may change the list (the controlling client, in any state) is the component's
//! business; this type only keeps the list. A list driver service reads it through
//! [`Cx::lists`](crate::service::Cx::lists): [`head`](Lists::head),
//! [`get`](Lists::get), [`iter_from`](Lists::iter_from), and notices changes by
//! [`revision`](Lists::revision).

use std::collections::HashMap;

use jaus::{CommandCode, JausMessage};

use crate::messages::{
    ConfirmElementRequest, DeleteElement, Element, ElementFormat, ElementRejection, Message,
    RejectElementRequest, ReportElement, ReportElementCount, ReportElementList, SetElement,
};

/// UID 65535 in Delete Element: every element.
pub const DELETE_ALL: u16 = 0xFFFF;

/// Default bound on the number of elements ([`Lists::new`]).
pub const DEFAULT_MAX_ELEMENTS: usize = 1024;

/// The element list of one component.
#[derive(Debug, Clone)]
pub struct Lists {
    elements: HashMap<u16, Element>,
    max_elements: usize,
    supported: Vec<u16>,
    user_defined: bool,
    revision: u64,
}

impl Default for Lists {
    fn default() -> Self {
        Self::new(DEFAULT_MAX_ELEMENTS)
    }
}

impl Lists {
    /// An empty list holding at most `max_elements` elements. Every element holding a
    /// JAUS message is accepted until [`support`](Self::support) narrows it; elements of
    /// a user-defined format are refused until [`allow_user_defined`](Self::allow_user_defined).
    pub fn new(max_elements: usize) -> Self {
        Self {
            elements: HashMap::new(),
            max_elements,
            supported: Vec::new(),
            user_defined: false,
            revision: 0,
        }
    }

    /// Accepts elements holding message `code` (a list driver calls this for its
    /// element type, e.g. Set Local Waypoint). Once one code is named, elements holding
    /// any other message are refused (Unsupported Element Type).
    pub fn support(&mut self, code: CommandCode) {
        if !self.supported.contains(&code.0) {
            self.supported.push(code.0);
        }
    }

    /// Accepts (or refuses) elements whose format is user-defined.
    pub fn allow_user_defined(&mut self, allow: bool) {
        self.user_defined = allow;
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.elements.len()
    }

    /// Whether the list is empty.
    pub fn is_empty(&self) -> bool {
        self.elements.is_empty()
    }

    /// The bound on the number of elements.
    pub fn max_elements(&self) -> usize {
        self.max_elements
    }

    /// Counts every change of the list (a list driver compares it to notice edits).
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// UID of the head element (the one whose previous UID is 0).
    pub fn head(&self) -> Option<u16> {
        self.elements
            .values()
            .find(|e| e.previous_uid == 0)
            .map(|e| e.uid)
    }

    /// The element `uid`.
    pub fn get(&self, uid: u16) -> Option<&Element> {
        self.elements.get(&uid)
    }

    /// The elements in list order from `uid` (itself first), following the next UIDs
    /// to the tail, or once round a circular list.
    pub fn iter_from(&self, uid: u16) -> impl Iterator<Item = &Element> + '_ {
        let mut at = self.elements.get(&uid).map(|e| e.uid);
        let mut steps = 0usize;
        std::iter::from_fn(move || {
            let e = self.elements.get(&at?)?;
            steps += 1;
            at = (e.next_uid != 0 && e.next_uid != uid && steps < self.elements.len())
                .then_some(e.next_uid);
            Some(e)
        })
    }

    /// The UIDs in list order from the head.
    pub fn uids(&self) -> Vec<u16> {
        self.head()
            .map(|h| self.iter_from(h).map(|e| e.uid).collect())
            .unwrap_or_default()
    }

    /// Removes every element.
    pub fn clear(&mut self) {
        if !self.elements.is_empty() {
            self.elements.clear();
            self.revision += 1;
        }
    }

    /// Stores `elements` as one transaction (see the module documentation).
    pub fn set(&mut self, elements: &[Element]) -> Result<(), ElementRejection> {
        let incoming: Vec<u16> = elements.iter().map(|e| e.uid).collect();
        for e in elements {
            if e.uid == 0 || e.uid == DELETE_ALL {
                return Err(ElementRejection::InvalidElementId);
            }
            self.check_type(e)?;
            let known = |u: u16| u == 0 || self.elements.contains_key(&u) || incoming.contains(&u);
            if e.previous_uid == e.uid || !known(e.previous_uid) {
                return Err(ElementRejection::InvalidPreviousElement);
            }
            if e.next_uid == e.uid || !known(e.next_uid) {
                return Err(ElementRejection::InvalidNextElement);
            }
        }
        let mut work = self.elements.clone();
        for e in elements {
            work.insert(e.uid, e.clone());
            if let Some(p) = work.get_mut(&e.previous_uid) {
                p.next_uid = e.uid;
            }
            if let Some(n) = work.get_mut(&e.next_uid) {
                // The closing link of a circular list leaves the head's previous at 0.
                if n.previous_uid != 0 || e.previous_uid == 0 || n.next_uid == 0 {
                    n.previous_uid = e.uid;
                }
            }
        }
        if work.len() > self.max_elements {
            return Err(ElementRejection::OutOfMemory);
        }
        validate(&work)?;
        self.elements = work;
        self.revision += 1;
        Ok(())
    }

    /// Removes the elements `uids` ([`DELETE_ALL`] removes every one), re-linking their
    /// neighbours. Every UID must exist, or nothing is removed.
    pub fn delete(&mut self, uids: &[u16]) -> Result<(), ElementRejection> {
        if uids.contains(&DELETE_ALL) {
            self.clear();
            return Ok(());
        }
        if uids.iter().any(|u| !self.elements.contains_key(u)) {
            return Err(ElementRejection::ElementIdNotFound);
        }
        for &uid in uids {
            let Some(gone) = self.elements.remove(&uid) else {
                continue;
            };
            for e in self.elements.values_mut() {
                if e.next_uid == uid {
                    e.next_uid = gone.next_uid;
                }
                if e.previous_uid == uid {
                    e.previous_uid = gone.previous_uid;
                }
                if e.next_uid == e.uid {
                    e.next_uid = 0;
                }
            }
        }
        self.revision += 1;
        Ok(())
    }

    fn check_type(&self, e: &Element) -> Result<(), ElementRejection> {
        match e.format {
            ElementFormat::JausMessage => {
                let Some(Ok(m)) = e.message() else {
                    return Err(ElementRejection::UnsupportedElementType);
                };
                if self.supported.is_empty() || self.supported.contains(&m.code().0) {
                    Ok(())
                } else {
                    Err(ElementRejection::UnsupportedElementType)
                }
            }
            ElementFormat::UserDefined if self.user_defined => Ok(()),
            _ => Err(ElementRejection::UnsupportedElementType),
        }
    }

    /// Handles a List Manager message: Set Element and Delete Element (whose sender the
    /// caller has checked) and the three queries. `None` for any other message and for
    /// Query Element of an unknown UID (the List Manager does not answer that).
    pub fn handle(&mut self, msg: &Message) -> Option<Message> {
        match msg {
            Message::SetElement(SetElement {
                request_id,
                elements,
            }) => Some(answer(*request_id, self.set(elements))),
            Message::DeleteElement(DeleteElement {
                request_id,
                element_uids,
            }) => Some(answer(*request_id, self.delete(element_uids))),
            Message::QueryElement(q) => self
                .get(q.element_uid)
                .map(|e| ReportElement { element: e.clone() }.into()),
            Message::QueryElementList(_) => Some(
                ReportElementList {
                    element_uids: self.uids(),
                }
                .into(),
            ),
            Message::QueryElementCount(_) => Some(
                ReportElementCount {
                    element_count: u16::try_from(self.len()).unwrap_or(u16::MAX),
                }
                .into(),
            ),
            _ => None,
        }
    }

    /// Whether `code` is a List Manager message this type handles.
    pub fn handles(code: CommandCode) -> bool {
        [
            SetElement::CODE,
            DeleteElement::CODE,
            crate::messages::QueryElement::CODE,
            crate::messages::QueryElementList::CODE,
            crate::messages::QueryElementCount::CODE,
        ]
        .contains(&code)
    }
}

pub(crate) fn answer(request_id: u8, r: Result<(), ElementRejection>) -> Message {
    match r {
        Ok(()) => ConfirmElementRequest { request_id }.into(),
        Err(response_code) => RejectElementRequest {
            request_id,
            response_code,
        }
        .into(),
    }
}

/// Checks the rules of a valid list on `list`.
fn validate(list: &HashMap<u16, Element>) -> Result<(), ElementRejection> {
    if list.is_empty() {
        return Ok(());
    }
    let heads: Vec<u16> = list
        .values()
        .filter(|e| e.previous_uid == 0)
        .map(|e| e.uid)
        .collect();
    let [head] = heads[..] else {
        return Err(ElementRejection::InvalidPreviousElement);
    };
    for e in list.values() {
        if e.previous_uid != 0 {
            match list.get(&e.previous_uid) {
                Some(p) if p.next_uid == e.uid && p.uid != e.uid => {}
                _ => return Err(ElementRejection::InvalidPreviousElement),
            }
        }
        if e.next_uid != 0 {
            match list.get(&e.next_uid) {
                Some(n) if n.uid != e.uid && n.previous_uid == e.uid => {}
                // The closing link of a circular list.
                Some(n) if n.uid == head => {}
                _ => return Err(ElementRejection::InvalidNextElement),
            }
        }
    }
    let tails = list.values().filter(|e| e.next_uid == 0).count();
    let closing = list.values().filter(|e| e.next_uid == head).count();
    if tails + closing != 1 {
        return Err(ElementRejection::InvalidNextElement);
    }
    // No orphans: the walk from the head reaches every element.
    let mut seen = 1usize;
    let mut at = list[&head].next_uid;
    while at != 0 && at != head && seen <= list.len() {
        seen += 1;
        at = list.get(&at).map_or(0, |e| e.next_uid);
    }
    if seen != list.len() {
        return Err(ElementRejection::InvalidNextElement);
    }
    Ok(())
}
