//! OpenJAUS's local component interface (docs/wire.md §8.5), both sides, sans-IO.
//!
//! OpenJAUS component processes do not speak JAUS to reach their node manager: they
//! check in over a control channel of fixed 8-byte datagrams (UDP port
//! [`CONTROL_PORT`] on the loopback address) to be given an address, then exchange raw
//! JAUS packets (no transport header; [`Framing::Raw`](super::Framing::Raw)) with the
//! node manager's data port [`DATA_PORT`], which learns where a component is from the
//! first packet it sends (its heartbeat). This module holds the control datagrams
//! ([`Control`]); a [`Node`](super::Node) serves the node-manager side
//! ([`Node::handle_component_control`](super::Node::handle_component_control),
//! [`Node::handle_component_data`](super::Node::handle_component_data)), and
//! [`udp::oj_check_in`](super::udp::oj_check_in) with an [`Attached`](super::Attached)
//! on [`Framing::Raw`](super::Framing::Raw) is the component side, so a component built
//! with this SDK runs under an OpenJAUS node manager.

use crate::{Address, CommandCode};

/// The node manager's control port (registration and lookups).
pub const CONTROL_PORT: u16 = 24627;
/// The node manager's data port (raw JAUS packets).
pub const DATA_PORT: u16 = 24629;

/// One control datagram. Addresses travel as four bytes in header order (instance,
/// component, node, subsystem); a zero byte in a lookup is a wildcard.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// 0x01, component → node manager: give me an address for component id `component`
    /// (`data_port`: the component's data socket, which OpenJAUS's node manager
    /// ignores).
    CheckIn {
        /// The component id.
        component: u8,
        /// The component's data port.
        data_port: u16,
    },
    /// 0x02, node manager → component: the address assigned.
    ReportAddress(Address),
    /// 0x03, component → node manager: the component leaves.
    CheckOut(Address),
    /// 0x04: is this address in the system tree?
    VerifyAddress(Address),
    /// 0x05: the answer.
    AddressVerified(bool),
    /// 0x06: the first component anywhere in the system with this id.
    GetComponentAddressList {
        /// The component id.
        component: u8,
    },
    /// 0x07: its address (`None`: all zero on the wire).
    ComponentAddressList(Option<Address>),
    /// 0x08: resolve an address whose zero bytes are wildcards.
    LookupAddress(Address),
    /// 0x09: the address found, and whether one was.
    LookupAddressResponse {
        /// The address (as asked when not found).
        address: Address,
        /// Whether it was found.
        valid: bool,
    },
    /// 0x0A: a component whose services take (`output` false) or send (`output` true)
    /// this message.
    LookupServiceAddress {
        /// The message.
        code: CommandCode,
        /// Output rather than input message.
        output: bool,
    },
    /// 0x0B: its address, and whether one was found.
    LookupServiceAddressResponse {
        /// The address found (zero when none).
        address: Address,
        /// Whether one was found.
        found: bool,
    },
    /// 0x0E: is the node manager up?
    ReadyCheck,
    /// 0x0F: it is.
    ReportReady,
}

/// Why a control datagram was not read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ControlError {
    /// Control datagrams are exactly 8 bytes.
    #[error("an OpenJAUS control datagram is 8 bytes, not {0}")]
    Length(usize),
    /// An opcode this side does not serve (0x0C/0x0D are defined but never answered by
    /// OpenJAUS either).
    #[error("unknown OpenJAUS control opcode 0x{0:02X}")]
    Opcode(u8),
}

fn addr(b: &[u8]) -> Address {
    Address::new(b[3], b[2], b[1], b[0])
}

fn put(a: Address, b: &mut [u8]) {
    b.copy_from_slice(&[a.instance, a.component, a.node, a.subsystem]);
}

const ZERO: Address = Address::new(0, 0, 0, 0);

impl Control {
    /// The 8 bytes on the wire.
    pub fn encode(&self) -> [u8; 8] {
        let mut b = [0u8; 8];
        match *self {
            Control::CheckIn {
                component,
                data_port,
            } => {
                b[0] = 0x01;
                b[1] = component;
                b[2..4].copy_from_slice(&data_port.to_le_bytes());
            }
            Control::ReportAddress(a) => {
                b[0] = 0x02;
                put(a, &mut b[1..5]);
            }
            Control::CheckOut(a) => {
                b[0] = 0x03;
                put(a, &mut b[1..5]);
            }
            Control::VerifyAddress(a) => {
                b[0] = 0x04;
                put(a, &mut b[1..5]);
            }
            Control::AddressVerified(v) => {
                b[0] = 0x05;
                b[1] = u8::from(v);
            }
            Control::GetComponentAddressList { component } => {
                b[0] = 0x06;
                b[1] = component;
            }
            Control::ComponentAddressList(a) => {
                b[0] = 0x07;
                put(a.unwrap_or(ZERO), &mut b[1..5]);
            }
            Control::LookupAddress(a) => {
                b[0] = 0x08;
                put(a, &mut b[1..5]);
            }
            Control::LookupAddressResponse { address, valid } => {
                b[0] = 0x09;
                put(address, &mut b[1..5]);
                b[5] = u8::from(valid);
            }
            Control::LookupServiceAddress { code, output } => {
                b[0] = 0x0A;
                b[5..7].copy_from_slice(&code.0.to_le_bytes());
                b[7] = u8::from(output);
            }
            Control::LookupServiceAddressResponse { address, found } => {
                b[0] = 0x0B;
                put(address, &mut b[1..5]);
                b[5] = u8::from(found);
            }
            Control::ReadyCheck => b[0] = 0x0E,
            Control::ReportReady => b[0] = 0x0F,
        }
        b
    }

    /// Reads a control datagram.
    pub fn decode(b: &[u8]) -> Result<Control, ControlError> {
        if b.len() != 8 {
            return Err(ControlError::Length(b.len()));
        }
        Ok(match b[0] {
            0x01 => Control::CheckIn {
                component: b[1],
                data_port: u16::from_le_bytes([b[2], b[3]]),
            },
            0x02 => Control::ReportAddress(addr(&b[1..5])),
            0x03 => Control::CheckOut(addr(&b[1..5])),
            0x04 => Control::VerifyAddress(addr(&b[1..5])),
            0x05 => Control::AddressVerified(b[1] == 1),
            0x06 => Control::GetComponentAddressList { component: b[1] },
            0x07 => {
                let a = addr(&b[1..5]);
                Control::ComponentAddressList((a != ZERO).then_some(a))
            }
            0x08 => Control::LookupAddress(addr(&b[1..5])),
            0x09 => Control::LookupAddressResponse {
                address: addr(&b[1..5]),
                valid: b[5] == 1,
            },
            0x0A => Control::LookupServiceAddress {
                code: CommandCode(u16::from_le_bytes([b[5], b[6]])),
                output: b[7] == 1,
            },
            0x0B => Control::LookupServiceAddressResponse {
                address: addr(&b[1..5]),
                found: b[5] == 1,
            },
            0x0E => Control::ReadyCheck,
            0x0F => Control::ReportReady,
            op => return Err(ControlError::Opcode(op)),
        })
    }
}

/// Whether `a` matches `pattern`, whose zero bytes are wildcards.
pub fn matches_wildcard(pattern: Address, a: Address) -> bool {
    let ok = |p: u8, v: u8| p == 0 || p == v;
    ok(pattern.subsystem, a.subsystem)
        && ok(pattern.node, a.node)
        && ok(pattern.component, a.component)
        && ok(pattern.instance, a.instance)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_datagrams_are_the_documented_bytes_and_round_trip() {
        // CHECK_IN for a Global Pose Sensor whose data socket is port 0x1234.
        let c = Control::CheckIn {
            component: 38,
            data_port: 0x1234,
        };
        assert_eq!(c.encode(), [0x01, 38, 0x34, 0x12, 0, 0, 0, 0]);
        // REPORT_ADDRESS 10.1.38.2: instance, component, node, subsystem.
        let r = Control::ReportAddress(Address::new(10, 1, 38, 2));
        assert_eq!(r.encode(), [0x02, 2, 38, 1, 10, 0, 0, 0]);
        let all = [
            c,
            r,
            Control::CheckOut(Address::new(1, 2, 3, 4)),
            Control::VerifyAddress(Address::new(1, 2, 3, 4)),
            Control::AddressVerified(true),
            Control::GetComponentAddressList { component: 33 },
            Control::ComponentAddressList(None),
            Control::ComponentAddressList(Some(Address::new(1, 1, 33, 1))),
            Control::LookupAddress(Address::new(0, 0, 33, 0)),
            Control::LookupAddressResponse {
                address: Address::new(1, 1, 33, 1),
                valid: true,
            },
            Control::LookupServiceAddress {
                code: CommandCode(0x0405),
                output: false,
            },
            Control::LookupServiceAddressResponse {
                address: Address::new(1, 1, 33, 1),
                found: true,
            },
            Control::ReadyCheck,
            Control::ReportReady,
        ];
        for m in all {
            assert_eq!(Control::decode(&m.encode()), Ok(m));
        }
        assert_eq!(Control::decode(&[1, 2, 3]), Err(ControlError::Length(3)));
        assert_eq!(
            Control::decode(&[0x0C, 0, 0, 0, 0, 0, 0, 0]),
            Err(ControlError::Opcode(0x0C))
        );
        assert!(matches_wildcard(
            Address::new(0, 0, 33, 0),
            Address::new(1, 1, 33, 1)
        ));
        assert!(!matches_wildcard(
            Address::new(0, 0, 33, 2),
            Address::new(1, 1, 33, 1)
        ));
    }
}
