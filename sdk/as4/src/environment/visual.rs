//! The Visual Sensor service's own answers, shared by the services extending it over an
//! RA 3.3 Visual Sensor (Still Image, Digital Video): the sensor's capabilities (its
//! name), configuration (always Active), placement (unknown over RA 3.3), and a
//! configuration accepted only where it leaves the sensor as it is.

use jaus::Address;

use super::SENSOR_ID;
use crate::machined::On;
use crate::messages::services::transport::event::Receive;
use crate::messages::services::visual_sensor as parent;
use crate::messages::{
    ConfirmSensorConfiguration, ConfirmSensorConfigurationVariant as Confirmed,
    ConfirmSensorConfigurationVariantVisualSensorErrorRec as VisualError,
    ConfirmSensorConfigurationVariantVisualSensorErrorRecCode as VisualCode,
    QuerySensorGeometricProperties, QueryVisualSensorCapabilities, QueryVisualSensorConfiguration,
    ReportSensorGeometricProperties, ReportSensorGeometricPropertiesSequence as Placement,
    ReportSensorGeometricPropertiesSequenceVariant as PlacementVariant,
    ReportSensorGeometricPropertiesSequenceVariantNoVariant as NoPlacement,
    ReportVisualSensorCapabilities, ReportVisualSensorCapabilitiesRec,
    ReportVisualSensorConfiguration, SensorIdRec, SensorStateEnum, SetVisualSensorConfiguration,
    VisualSensorConfigurationRec,
};

/// A service's data over an RA 3.3 Visual Sensor: its Visual Sensor answers come from
/// here.
pub trait OverVisualSensor {
    /// The RA 3.3 Visual Sensor's address.
    fn visual_sensor(&self) -> Address;
}

impl<T: OverVisualSensor> parent::VisualSensor for On<'_, T> {
    fn send_report_visual_sensor_capabilities(
        &mut self,
        msg: &QueryVisualSensorCapabilities,
        transport: &Receive,
    ) {
        let list = msg
            .query_visual_sensor_capabilities_list
            .iter()
            .filter(|r| r.sensor_id == SENSOR_ID)
            .map(|_| ReportVisualSensorCapabilitiesRec {
                sensor_id: SENSOR_ID,
                sensor_name: format!("RA 3.3 visual sensor {}", self.svc.visual_sensor()),
                ..Default::default()
            })
            .collect();
        self.reply(
            transport,
            ReportVisualSensorCapabilities {
                visual_sensor_capabilities_list: list,
            },
        );
    }

    fn send_report_visual_sensor_configuration(
        &mut self,
        msg: &QueryVisualSensorConfiguration,
        transport: &Receive,
    ) {
        // An RA 3.3 visual sensor takes an image whenever asked.
        let state = SensorStateEnum::Active;
        let list = msg
            .query_visual_sensor_configuration_list
            .iter()
            .filter(|r| r.sensor_id == SENSOR_ID)
            .map(|_| VisualSensorConfigurationRec {
                sensor_id: SENSOR_ID,
                sensor_state: Some(state),
                ..Default::default()
            })
            .collect();
        self.reply(
            transport,
            ReportVisualSensorConfiguration {
                visual_sensor_configuration_list: list,
            },
        );
    }

    fn send_report_sensor_geometric_properties(
        &mut self,
        msg: &QuerySensorGeometricProperties,
        transport: &Receive,
    ) {
        // Where the camera is on the vehicle is not known over RA 3.3.
        let list = msg
            .sensor_id_list
            .iter()
            .filter(|r| r.sensor_id == SENSOR_ID)
            .map(|r| Placement {
                sensor_id_rec: r.clone(),
                geometric_properties_variant: PlacementVariant::NoGeometricPropertiesVariant(
                    NoPlacement::default(),
                ),
            })
            .collect();
        self.reply(
            transport,
            ReportSensorGeometricProperties {
                geometric_properties_list: list,
            },
        );
    }

    fn update_visual_sensor_configuration(
        &mut self,
        msg: &SetVisualSensorConfiguration,
        transport: &Receive,
    ) {
        // Nothing of an RA 3.3 visual sensor is configurable this way: a sensor left
        // Active is accepted, anything else refused.
        let confirm_sensor_list = msg
            .visual_sensor_configuration_list
            .iter()
            .map(|r| {
                let refuse = |code, why: &str| {
                    Confirmed::VisualSensorErrorRec(VisualError {
                        sensor_id: r.sensor_id,
                        visual_sensor_error_code: code,
                        error_message: why.into(),
                    })
                };
                if r.sensor_id != SENSOR_ID {
                    return refuse(VisualCode::UnknownSensorId, "no such sensor");
                }
                let only_state = VisualSensorConfigurationRec {
                    sensor_id: r.sensor_id,
                    sensor_state: r.sensor_state,
                    ..Default::default()
                };
                if *r != only_state {
                    return refuse(
                        VisualCode::MultipleInvalidParameters,
                        "the RA 3.3 visual sensor has no such setting",
                    );
                }
                match r.sensor_state {
                    None | Some(SensorStateEnum::Active) => Confirmed::SensorIdRec(SensorIdRec {
                        sensor_id: r.sensor_id,
                    }),
                    Some(_) => refuse(
                        VisualCode::InvalidSensorState,
                        "the RA 3.3 visual sensor is always active",
                    ),
                }
            })
            .collect();
        self.reply(
            transport,
            ConfirmSensorConfiguration {
                request_id_rec: msg.request_id_rec.clone(),
                confirm_sensor_list,
            },
        );
    }
}
