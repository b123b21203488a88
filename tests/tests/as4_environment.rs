//! AS-4 Environment Sensing through the gateway: an AS-4 client fetches a still image of
//! the demo vehicle's RA 3.3 Visual Sensor through the Still Image service the gateway
//! presents (`jaus_as4::environment`), reads its capabilities and configuration, and
//! has a configuration it cannot give refused sensor by sensor.

use std::time::Duration;

use jaus::JausMessage;
use jaus_as4::{
    ConfirmSensorConfigurationVariant as Confirmed, CoordinateSystemEnum, Message,
    QueryStillImageData, QueryStillImageDataRec, QueryStillImageSensorCapabilities,
    QueryStillImageSensorCapabilitiesRec, QueryVisualSensorConfiguration,
    QueryVisualSensorConfigurationRec, RequestControl, RequestIdRec, SensorStateEnum,
    SetStillImageSensorConfiguration, StillImageFormatEnum, StillImageSensorConfigurationRec,
};

mod common;
use common::as4::As4Rig;

const PNG: &[u8] = b"\x89PNG\r\n\x1a\n";

struct Rig(As4Rig);

impl Rig {
    fn new() -> Self {
        // The node settles, the gateway finds the camera.
        Rig(As4Rig::demo_vehicle())
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        self.0.one_within(m, Duration::from_millis(500))
    }

    /// The PNG the RA 3.3 visual sensor last reported to the gateway.
    fn ra33_image(&self) -> Vec<u8> {
        let env = self.0.dual().gateway().node().env();
        let vs = env.targets().visual_sensor.expect("the camera found");
        match env.latest(vs, jaus::messages::ReportImage::CODE) {
            Some((_, jaus::messages::Message::ReportImage(r))) => r.data.clone(),
            other => panic!("no RA 3.3 image: {other:?}"),
        }
    }
}

#[test]
fn an_as4_client_fetches_a_still_image_of_the_ra33_camera() {
    let mut r = Rig::new();
    let Message::ReportStillImageData(d) = r.one(QueryStillImageData {
        query_still_image_data_list: vec![QueryStillImageDataRec {
            sensor_id: 1,
            report_coordinate_system: CoordinateSystemEnum::NativeCoordinateSystem,
            query_presence_vector: 0,
        }],
    }) else {
        panic!("no Report Still Image Data");
    };
    assert_eq!(d.still_image_data_list.len(), 1);
    let image = &d.still_image_data_list[0];
    assert_eq!(image.sensor_id, 1);
    assert_eq!(
        image.image_frame_format,
        StillImageFormatEnum::Png.to_repr()
    );
    assert!(image.image_frame.starts_with(PNG), "not a PNG");
    assert!(
        image.image_frame.len() > 1000,
        "{} bytes",
        image.image_frame.len()
    );
    // The RA 3.3 sensor's own image (the gateway polls it; the frame may be newer by
    // now, so compare with what it holds after the answer).
    assert_eq!(image.image_frame, r.ra33_image());
    println!("still image: {} bytes of PNG", image.image_frame.len());

    // Capabilities and configuration: PNG, the sensor active.
    let Message::ReportStillImageSensorCapabilities(c) = r.one(QueryStillImageSensorCapabilities {
        query_still_image_sensor_capabilities_list: vec![QueryStillImageSensorCapabilitiesRec {
            sensor_id: 1,
            query_presence_vector: 3,
        }],
    }) else {
        panic!("no capabilities");
    };
    assert!(c.still_image_sensor_list[0]
        .supported_image_formats
        .as_ref()
        .is_some_and(|f| f.png && !f.jpeg));
    let Message::ReportVisualSensorConfiguration(v) = r.one(QueryVisualSensorConfiguration {
        query_visual_sensor_configuration_list: vec![QueryVisualSensorConfigurationRec {
            sensor_id: 1,
            ..Default::default()
        }],
    }) else {
        panic!("no configuration");
    };
    assert_eq!(
        v.visual_sensor_configuration_list[0].sensor_state,
        Some(SensorStateEnum::Active)
    );
}

#[test]
fn a_configuration_the_camera_cannot_give_is_refused_sensor_by_sensor() {
    let mut r = Rig::new();
    let Message::ConfirmControl(_) = r.one(RequestControl { authority_code: 5 }) else {
        panic!("no Confirm Control");
    };
    let Message::ConfirmSensorConfiguration(c) = r.one(SetStillImageSensorConfiguration {
        request_id_rec: RequestIdRec { request_id: 7 },
        still_image_sensor_list: vec![
            StillImageSensorConfigurationRec {
                sensor_id: 1,
                frame_size: None,
                still_image_format: Some(StillImageFormatEnum::Png),
            },
            StillImageSensorConfigurationRec {
                sensor_id: 1,
                frame_size: None,
                still_image_format: Some(StillImageFormatEnum::Jpeg),
            },
            StillImageSensorConfigurationRec {
                sensor_id: 9,
                ..Default::default()
            },
        ],
    }) else {
        panic!("no Confirm Sensor Configuration");
    };
    assert_eq!(c.request_id_rec.request_id, 7);
    assert_eq!(c.confirm_sensor_list.len(), 3);
    assert!(matches!(&c.confirm_sensor_list[0], Confirmed::SensorIdRec(s) if s.sensor_id == 1));
    let Confirmed::StillImageSensorErrorRec(e) = &c.confirm_sensor_list[1] else {
        panic!("{:?}", c.confirm_sensor_list[1]);
    };
    assert!(e.error_message.contains("Png"), "{e:?}");
    let Confirmed::StillImageSensorErrorRec(e) = &c.confirm_sensor_list[2] else {
        panic!("{:?}", c.confirm_sensor_list[2]);
    };
    assert_eq!(e.sensor_id, 9);
}
