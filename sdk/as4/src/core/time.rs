//! Time (`urn:jaus:jss:core:Time` 1.1): the component's UTC clock.
//!
//! The runtime reads no clock: the owner tells the component the wall-clock time once
//! ([`Time::set_utc`]: UTC since 1970-01-01 at an `Instant`), and the clock runs on with
//! the `now` of each call. Set Time (from the controlling client) moves it: the time
//! stamp sets the day of the month and the time of day, the date stamp the date;
//! fields not sent keep their value. Until the clock is known, Report Time carries
//! neither field (both are optional).
//!
//! The clock is the one RA 3.3 components keep ([`jaus::clock::Clock`]); this module
//! holds the AS-4 wire mapping only: AS-4's time and date stamps as the clock's fields,
//! and Query Time, Report Time and Set Time.

use std::time::{Duration, Instant};

use jaus::clock::{Clock, Date, TimeOfDay};

use crate::messages::{DateStamp, QueryTime, ReportTime, SetTime, TimeStamp};

/// The UTC clock of a component.
#[derive(Debug, Clone, Copy, Default)]
pub struct Time {
    clock: Clock,
}

impl Time {
    /// UTC (since 1970-01-01) is `utc` at `now`.
    pub fn set_utc(&mut self, now: Instant, utc: Duration) {
        self.clock.set_utc(now, utc);
    }

    /// Whether the clock was ever set.
    pub fn is_set(&self) -> bool {
        self.clock.is_set()
    }

    /// UTC at `now`.
    pub fn utc(&self, now: Instant) -> Option<Duration> {
        self.clock.utc(now)
    }

    /// The time and date stamps at `now`.
    pub fn stamps(&self, now: Instant) -> Option<(TimeStamp, DateStamp)> {
        self.clock
            .stamps(now)
            .map(|(time, date)| (time.into(), date.into()))
    }

    /// Report Time with the fields Query Time asks for (bit 0 time, bit 1 date).
    pub fn report(&self, now: Instant, q: &QueryTime) -> ReportTime {
        let stamps = self.stamps(now);
        ReportTime {
            time_stamp: stamps
                .filter(|_| q.presence_vector & 1 != 0)
                .map(|(t, _)| t),
            date_stamp: stamps
                .filter(|_| q.presence_vector & 2 != 0)
                .map(|(_, d)| d),
        }
    }

    /// Set Time: `Err` names an impossible time or date (nothing changes then).
    pub fn set(&mut self, now: Instant, msg: &SetTime) -> Result<(), String> {
        let time = msg.time_stamp.as_ref().map(TimeOfDay::from);
        let date = msg.date_stamp.as_ref().map(Date::from);
        self.clock.apply(now, time, date)
    }
}

impl From<&TimeStamp> for TimeOfDay {
    fn from(t: &TimeStamp) -> Self {
        TimeOfDay {
            millisecond: t.millisecond,
            second: t.second,
            minute: t.minute,
            hour: t.hour,
            day: t.day,
        }
    }
}

impl From<TimeOfDay> for TimeStamp {
    fn from(t: TimeOfDay) -> Self {
        TimeStamp {
            millisecond: t.millisecond,
            second: t.second,
            minute: t.minute,
            hour: t.hour,
            day: t.day,
            reserved: 0,
        }
    }
}

impl From<&DateStamp> for Date {
    fn from(d: &DateStamp) -> Self {
        Date {
            day: d.day,
            month: d.month,
            year: d.year,
        }
    }
}

impl From<Date> for DateStamp {
    fn from(d: Date) -> Self {
        DateStamp {
            day: d.day,
            month: d.month,
            year: d.year,
            reserved: 0,
        }
    }
}
