//! Issue 37: the main job (`jaus demo`) runs without a single warning or error in its log.
//! (It once logged the Primitive Driver refusing a Set Wrench Effort from the Reflexive
//! Driver: the spooler borrows the Primitive Driver for the mission's payload action,
//! and the Reflexive Driver's brake crossed the Reject Component Control. Such a
//! crossing is normal in JAUS and is now logged at debug; a command from a sender that
//! never had control is still a warning.)

use std::sync::{Arc, Mutex};

#[derive(Clone)]
struct LogBuffer(Arc<Mutex<Vec<u8>>>);

impl std::io::Write for LogBuffer {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn the_demo_logs_no_warning_and_no_error() {
    let log = Arc::new(Mutex::new(Vec::new()));
    let buf = LogBuffer(log.clone());
    let subscriber = tracing_subscriber::fmt()
        .with_writer(move || buf.clone())
        .with_ansi(false)
        .with_max_level(tracing_subscriber::filter::LevelFilter::WARN)
        .finish();
    let _guard = tracing_subscriber::util::SubscriberInitExt::set_default(subscriber);
    let run = jaus_sim::demo::run(&jaus_sim::demo::Options::default(), |_| {}).expect("the demo");
    assert!(!run.legs.is_empty());
    let text = String::from_utf8_lossy(&log.lock().unwrap()).into_owned();
    assert!(text.is_empty(), "the demo logged:\n{text}");
}
