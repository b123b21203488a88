//! A service's guards and actions are the user's to write: an implementation of the
//! generated trait that leaves out a guard does not compile, and the error names it.
#[allow(unused, clippy::match_single_binding)]
mod guards {
    include!("../../../../../jaus-gen/tests/golden/hsm_guards.messages.rs");
    pub mod services {
        include!("../../../../../jaus-gen/tests/golden/hsm_guards.services.rs");
    }
}

use guards::services::throttle::{event::Received, Throttle};
use guards::SetSpeed;

struct Mine;

impl Throttle for Mine {
    fn is_too_fast(&self, msg: &SetSpeed) -> bool {
        msg.speed > 100
    }
    fn is_override(&self, from: &Received) -> bool {
        from.source == 1
    }
    fn apply(&mut self, msg: &SetSpeed) {
        let _ = msg;
    }
    fn refuse(&mut self, from: &Received, value1: &str) {
        let _ = (from, value1);
    }
}

fn main() {}
