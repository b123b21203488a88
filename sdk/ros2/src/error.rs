//! What can go wrong starting a bridge ([`Ros2Error`]), robot or vehicle mode.

/// What can go wrong starting a bridge.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Ros2Error {
    /// A setting is out of range or a name is not a ROS 2 name.
    #[error("ros2 configuration: {0}")]
    Config(String),
    /// The DDS participant, a topic, a reader or the writer could not be created.
    #[error("ros2 (DDS): {0}")]
    Dds(String),
    /// The JAUS node refused a component.
    #[error("ros2 (JAUS node): {0}")]
    Jaus(String),
}
