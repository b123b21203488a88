//! Why a component could not initialise.

/// Why a component could not initialise (returned by `initialize`): the component
/// enters Failure instead of Standby, and the runtime logs this message with the
/// component's name and address. Say what failed and what to check, e.g. "cannot open
/// /dev/ttyUSB0 (the GPS receiver): permission denied; add the user to group dialout".
///
/// Made from a message (`InitError::new`, `"…".into()`, `format!(…).into()`) or from
/// an I/O error with `?`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct InitError {
    message: String,
}

impl InitError {
    /// An error with this message.
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }

    /// The message.
    pub fn message(&self) -> &str {
        &self.message
    }
}

impl From<String> for InitError {
    fn from(message: String) -> Self {
        Self::new(message)
    }
}

impl From<&str> for InitError {
    fn from(message: &str) -> Self {
        Self::new(message)
    }
}

impl From<std::io::Error> for InitError {
    fn from(e: std::io::Error) -> Self {
        Self::new(e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn made_from_text_or_an_io_error() {
        assert_eq!(InitError::new("no GPS fix").to_string(), "no GPS fix");
        let e: InitError = format!("port {} busy", 3).into();
        assert_eq!(e.message(), "port 3 busy");
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "/dev/ttyUSB0 not found");
        let e: InitError = io.into();
        assert_eq!(e.to_string(), "/dev/ttyUSB0 not found");
    }
}
