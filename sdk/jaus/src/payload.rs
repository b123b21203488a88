//! Payload data elements: the values of Set/Report Payload Data Element, which can only
//! be read with the type codes of the payload's interfaces (from its Report Payload
//! Interface). The messages keep the elements as raw bytes, so they always round-trip;
//! this module reads and writes them given those type codes.
//!
//! ```
//! use jaus::messages::{PayloadValue, SetPayloadDataElement};
//! use jaus::payload::{DataElement, PayloadTypes};
//!
//! // Interface 1 is an unsigned short, interface 2 a boolean.
//! let types = PayloadTypes::new(vec![5, 18]);
//! let set = SetPayloadDataElement::with_elements(&[
//!     DataElement { index: 2, value: PayloadValue::Boolean(1) },
//!     DataElement { index: 1, value: PayloadValue::UnsignedShort(600) },
//! ])
//! .unwrap();
//! assert_eq!(set.elements, [2, 1, 1, 0x58, 0x02]);
//! assert_eq!(set.data_elements(&types).unwrap()[1].value, PayloadValue::UnsignedShort(600));
//! ```

use crate::codec::{DecodeError, DecodeErrorKind, EncodeError, Reader, Writer};
use crate::messages::{
    PayloadValue, ReportPayloadDataElement, ReportPayloadInterface, SetPayloadDataElement,
};

/// Type codes of a payload's interfaces, in interface-index order (index 1 first).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PayloadTypes {
    codes: Vec<u8>,
}

impl PayloadTypes {
    /// From the type codes of the interfaces, in index order.
    pub fn new(codes: Vec<u8>) -> Self {
        Self { codes }
    }

    /// Type codes of the command interfaces of a payload interface (for Set Payload Data
    /// Element).
    pub fn commands(interface: &ReportPayloadInterface) -> Self {
        Self::new(
            interface
                .command_interfaces
                .iter()
                .map(|i| i.type_code)
                .collect(),
        )
    }

    /// Type codes of the information interfaces of a payload interface (for Report
    /// Payload Data Element).
    pub fn information(interface: &ReportPayloadInterface) -> Self {
        Self::new(
            interface
                .information_interfaces
                .iter()
                .map(|i| i.type_code)
                .collect(),
        )
    }

    /// The type code of 1-based interface `index`.
    pub fn type_of(&self, index: u8) -> Option<u8> {
        usize::from(index)
            .checked_sub(1)
            .and_then(|i| self.codes.get(i))
            .copied()
    }
}

/// One data element: an interface index and its value.
#[derive(Debug, Clone, PartialEq)]
pub struct DataElement {
    /// 1-based interface index.
    pub index: u8,
    /// The value; its variant is the interface's type code.
    pub value: PayloadValue,
}

/// Reads `count` elements from `bytes`.
pub fn decode_elements(
    count: u8,
    bytes: &[u8],
    types: &PayloadTypes,
) -> Result<Vec<DataElement>, DecodeError> {
    let mut r = Reader::new(bytes);
    let mut out = Vec::with_capacity(usize::from(count).min(bytes.len()));
    for _ in 0..count {
        let at = r.offset();
        let index = u8::from_le_bytes(r.array()?);
        let code = types.type_of(index).ok_or_else(|| {
            DecodeError::new(
                DecodeErrorKind::UndefinedValue {
                    value: u64::from(index),
                },
                at,
            )
            .in_field("DataElement.index")
        })?;
        let value = PayloadValue::decode_value(u64::from(code), &mut r)
            .map_err(|e| e.in_field("DataElement.value"))?;
        out.push(DataElement { index, value });
    }
    r.finish()?;
    Ok(out)
}

/// Writes elements: for each, the index then the value without its type code.
pub fn encode_elements(elements: &[DataElement]) -> Result<(u8, Vec<u8>), EncodeError> {
    let count = u8::try_from(elements.len()).map_err(|_| EncodeError::CountOverflow {
        field: "DataElement",
        count: elements.len(),
        max: 255,
    })?;
    let len = elements.iter().map(|e| 1 + e.value.value_len()).sum();
    let mut out = vec![0u8; len];
    let mut w = Writer::new(&mut out);
    for e in elements {
        w.put(&[e.index])?;
        e.value.encode_value(&mut w)?;
    }
    Ok((count, out))
}

/// The data-element API of the two messages that carry payload values.
macro_rules! data_element_api {
    ($($msg:ident: $side:literal;)*) => {$(
        impl $msg {
            #[doc = concat!("The message carrying `elements` (indexes into the ", $side, " interfaces).")]
            pub fn with_elements(elements: &[DataElement]) -> Result<Self, EncodeError> {
                let (element_count, elements) = encode_elements(elements)?;
                Ok(Self { element_count, elements })
            }

            #[doc = concat!("The elements, read with the type codes of the payload's ", $side, " interfaces.")]
            pub fn data_elements(&self, interfaces: &PayloadTypes) -> Result<Vec<DataElement>, DecodeError> {
                decode_elements(self.element_count, &self.elements, interfaces)
            }
        }
    )*};
}

data_element_api! {
    SetPayloadDataElement: "command";
    ReportPayloadDataElement: "information";
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codec::{Decode, Encode};
    use crate::messages::{PayloadCommandInterface, PayloadInformationInterface};

    #[test]
    fn an_interface_round_trips_and_types_its_data_elements() {
        let cmd = PayloadCommandInterface {
            identifier: "flail speed".into(),
            type_code: 5,
            units: 12,
            blocking: 1,
            min_value: PayloadValue::UnsignedShort(0),
            default_value: PayloadValue::UnsignedShort(100),
            max_value: PayloadValue::UnsignedShort(900),
            enumeration: String::new(),
            hmi_recommendation: Some(3),
            hmi_x: None,
            hmi_y: None,
            hmi_width: None,
            hmi_height: None,
        };
        let info = PayloadInformationInterface {
            identifier: "armed".into(),
            command_association: 1,
            type_code: 18,
            units: 0,
            min_value: PayloadValue::Boolean(0),
            default_value: PayloadValue::Boolean(0),
            max_value: PayloadValue::Boolean(1),
            enumeration: "off,on".into(),
            hmi_recommendation: Some(1),
            hmi_x: None,
            hmi_y: None,
            hmi_width: None,
            hmi_height: None,
        };
        let iface = ReportPayloadInterface {
            has_hmi_recommendation: true,
            has_hmi_x: false,
            has_hmi_y: false,
            has_hmi_width: false,
            has_hmi_height: false,
            command_interface_count: 0,
            information_interface_count: 0,
            command_interfaces: vec![cmd.clone()],
            information_interfaces: vec![info],
        };
        let bytes = iface.to_bytes().unwrap();
        // Presence vector, counts, then the identifier as a C string.
        assert_eq!(&bytes[..3], &[0b1, 1, 1]);
        assert_eq!(&bytes[3..15], b"flail speed\0");
        let back = ReportPayloadInterface::from_bytes(&bytes).unwrap();
        assert_eq!(back.command_interfaces[0], cmd);
        assert_eq!(back.command_interface_count, 1);

        let report = ReportPayloadDataElement::with_elements(&[DataElement {
            index: 1,
            value: PayloadValue::Boolean(1),
        }])
        .unwrap();
        let values = report
            .data_elements(&PayloadTypes::information(&back))
            .unwrap();
        assert_eq!(values[0].value, PayloadValue::Boolean(1));

        // A value whose type disagrees with its interface's type code is refused.
        let mut wrong = iface.clone();
        wrong.command_interfaces[0].max_value = PayloadValue::Integer(900);
        assert!(matches!(
            wrong.to_bytes(),
            Err(EncodeError::TagMismatch { .. })
        ));
        // So is an HMI field without its flag.
        let mut wrong = iface;
        wrong.has_hmi_recommendation = false;
        assert!(matches!(
            wrong.to_bytes(),
            Err(EncodeError::PresenceMismatch { .. })
        ));
    }

    #[test]
    fn unknown_index_and_short_data_are_typed_errors() {
        let types = PayloadTypes::new(vec![2]);
        assert!(
            decode_elements(1, &[2, 0, 0, 0, 0], &types).is_err(),
            "index 2 has no interface"
        );
        assert!(
            decode_elements(1, &[1, 0, 0], &types).is_err(),
            "an integer needs 4 bytes"
        );
        assert!(
            decode_elements(1, &[1, 0, 0, 0, 0, 9], &types).is_err(),
            "trailing bytes"
        );
        assert_eq!(
            decode_elements(1, &[1, 1, 0, 0, 0], &types).unwrap()[0].value,
            PayloadValue::Integer(1)
        );
    }
}
