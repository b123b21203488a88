//! Time (`urn:jaus:jss:core:Time` 1.1): the component's UTC clock.
//!
//! The runtime reads no clock: the owner tells the component the wall-clock time once
//! ([`Time::set_utc`]: UTC since 1970-01-01 at an `Instant`), and the clock runs on with
//! the `now` of each call. Set Time (from the controlling client) moves it: the time
//! stamp sets the day of the month and the time of day, the date stamp the date;
//! fields not sent keep their value. Until the clock is known, Report Time carries
//! neither field (both are optional).

use std::time::{Duration, Instant};

use jaus::calendar::Civil;

use crate::messages::{DateStamp, QueryTime, ReportTime, SetTime, TimeStamp};

/// The UTC clock of a component.
#[derive(Debug, Clone, Copy, Default)]
pub struct Time {
    anchor: Option<(Instant, Duration)>,
}

impl Time {
    /// UTC (since 1970-01-01) is `utc` at `now`.
    pub fn set_utc(&mut self, now: Instant, utc: Duration) {
        self.anchor = Some((now, utc));
    }

    /// Whether the clock was ever set.
    pub fn is_set(&self) -> bool {
        self.anchor.is_some()
    }

    /// UTC at `now`.
    pub fn utc(&self, now: Instant) -> Option<Duration> {
        self.anchor
            .map(|(at, utc)| utc + now.saturating_duration_since(at))
    }

    /// The time and date stamps at `now`.
    pub fn stamps(&self, now: Instant) -> Option<(TimeStamp, DateStamp)> {
        let c = Civil::from_utc(self.utc(now)?);
        let time = TimeStamp {
            millisecond: c.millisecond as u16,
            second: c.second as u8,
            minute: c.minute as u8,
            hour: c.hour as u8,
            day: c.day as u8,
            reserved: 0,
        };
        let date = DateStamp {
            day: c.day as u8,
            month: c.month as u8,
            year: (c.year - 2000).clamp(0, 127) as u8,
            reserved: 0,
        };
        Some((time, date))
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
        let mut c = Civil::from_utc(self.utc(now).unwrap_or_default());
        if let Some(ds) = &msg.date_stamp {
            c.year = 2000 + i64::from(ds.year);
            c.month = u32::from(ds.month);
            c.day = u32::from(ds.day);
        }
        if let Some(ts) = &msg.time_stamp {
            c.day = u32::from(ts.day);
            c.hour = u32::from(ts.hour);
            c.minute = u32::from(ts.minute);
            c.second = u32::from(ts.second);
            c.millisecond = u32::from(ts.millisecond);
        }
        let utc = c.to_utc()?;
        self.set_utc(now, utc);
        Ok(())
    }
}
