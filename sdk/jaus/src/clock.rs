//! A component's UTC clock, as RA 3.3 (Set Time, Report Time, the time stamps of
//! reports) and AS-4's Time service (`urn:jaus:jss:core:Time`) both keep it: set once
//! from the shell or by Set Time, then running on with the `now` of each call. No wall
//! clock is read here; the time of day is derived from the `now` the owner is given,
//! so virtual-clock tests are deterministic.
//!
//! The clock speaks in the fields of the JAUS time and date stamps ([`TimeOfDay`],
//! [`Date`]), which RA 3.3 and AS-4 define alike; each side converts its own
//! `TimeStamp` and `DateStamp` to and from them (`From`: RA 3.3's below, AS-4's in
//! `jaus-as4`), and nothing more.
//!
//! ```
//! use jaus::clock::{Clock, Date, TimeOfDay};
//! use std::time::{Duration, Instant};
//!
//! let t0 = Instant::now();
//! let mut clock = Clock::default();
//! assert!(clock.stamps(t0).is_none());
//! let date = Date { day: 22, month: 11, year: 26 };
//! let time = TimeOfDay { millisecond: 250, second: 7, minute: 6, hour: 3, day: 22 };
//! clock.apply(t0, Some(time), Some(date)).unwrap();
//! let (t, d) = clock.stamps(t0 + Duration::from_secs(1)).unwrap();
//! assert_eq!((t.hour, t.minute, t.second, d.year), (3, 6, 8, 26));
//! ```

use std::time::{Duration, Instant};

use crate::calendar::Civil;
use crate::messages::{DateStamp, TimeStamp};

/// UTC as a duration since 1970-01-01T00:00:00Z, anchored to an [`Instant`] of the
/// owner's clock. Unset until [`set_utc`](Self::set_utc) or [`apply`](Self::apply).
#[derive(Debug, Clone, Copy, Default)]
pub struct Clock {
    anchor: Option<(Instant, Duration)>,
}

/// The fields of a JAUS time stamp: a time of day (UTC) with the day of the month.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TimeOfDay {
    /// Milliseconds, 0-999.
    pub millisecond: u16,
    /// Seconds, 0-59.
    pub second: u8,
    /// Minutes, 0-59.
    pub minute: u8,
    /// Hour, 0-23.
    pub hour: u8,
    /// Day of the month, 1-31.
    pub day: u8,
}

/// The fields of a JAUS date stamp.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Date {
    /// Day of the month, 1-31.
    pub day: u8,
    /// Month, 1-12.
    pub month: u8,
    /// Year minus 2000, 0-127.
    pub year: u8,
}

/// The first year of a date stamp (its `year` 0).
const EPOCH_YEAR: i64 = 2000;
/// The last `year` of a date stamp (7 bits).
const MAX_YEAR: i64 = 127;

impl Clock {
    /// UTC (since 1970-01-01) is `utc` at `now`.
    pub fn set_utc(&mut self, now: Instant, utc: Duration) {
        self.anchor = Some((now, utc));
    }

    /// Whether the clock was ever set.
    pub fn is_set(&self) -> bool {
        self.anchor.is_some()
    }

    /// UTC (since 1970-01-01) at `now`, when the clock is set.
    pub fn utc(&self, now: Instant) -> Option<Duration> {
        self.anchor
            .map(|(at, utc)| utc + now.saturating_duration_since(at))
    }

    /// The time and date stamps at `now`, when the clock is set (the year clamped to
    /// 2000-2127).
    pub fn stamps(&self, now: Instant) -> Option<(TimeOfDay, Date)> {
        let c = Civil::from_utc(self.utc(now)?);
        let time = TimeOfDay {
            millisecond: c.millisecond as u16,
            second: c.second as u8,
            minute: c.minute as u8,
            hour: c.hour as u8,
            day: c.day as u8,
        };
        let date = Date {
            day: c.day as u8,
            month: c.month as u8,
            year: (c.year - EPOCH_YEAR).clamp(0, MAX_YEAR) as u8,
        };
        Some((time, date))
    }

    /// Applies a Set Time at `now`: the time stamp replaces the day of the month and the
    /// time of day, the date stamp the calendar date. Fields not sent keep their current
    /// value (or 1970-01-01 / midnight when the clock was never set). `Err` names an
    /// impossible date or time; nothing changes then.
    pub fn apply(
        &mut self,
        now: Instant,
        time: Option<TimeOfDay>,
        date: Option<Date>,
    ) -> Result<(), String> {
        let mut c = Civil::from_utc(self.utc(now).unwrap_or_default());
        if let Some(d) = date {
            c.year = EPOCH_YEAR + i64::from(d.year);
            c.month = u32::from(d.month);
            c.day = u32::from(d.day);
        }
        if let Some(t) = time {
            c.day = u32::from(t.day);
            c.hour = u32::from(t.hour);
            c.minute = u32::from(t.minute);
            c.second = u32::from(t.second);
            c.millisecond = u32::from(t.millisecond);
        }
        let utc = c.to_utc()?;
        self.set_utc(now, utc);
        Ok(())
    }
}

// RA 3.3's stamps (`jaus::messages`): the wire mapping.

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

#[cfg(test)]
mod tests {
    use super::*;

    fn ra33(stamps: Option<(TimeOfDay, Date)>) -> Option<(TimeStamp, DateStamp)> {
        stamps.map(|(t, d)| (t.into(), d.into()))
    }

    #[test]
    fn set_time_then_read_stamps() {
        let t0 = Instant::now();
        let mut c = Clock::default();
        assert!(c.stamps(t0).is_none() && !c.is_set());
        let date = Date {
            day: 22,
            month: 11,
            year: 26,
        };
        let time = TimeOfDay {
            millisecond: 250,
            second: 7,
            minute: 6,
            hour: 3,
            day: 22,
        };
        assert!(c.apply(t0, Some(time), Some(date)).is_ok());
        let (ts, ds) = c.stamps(t0 + Duration::from_millis(1_000)).unwrap();
        assert_eq!(
            (ts.hour, ts.minute, ts.second, ts.millisecond, ts.day),
            (3, 6, 8, 250, 22)
        );
        assert_eq!((ds.year, ds.month, ds.day), (26, 11, 22));
        // An impossible date changes nothing.
        let bad = Date {
            day: 31,
            month: 2,
            year: 26,
        };
        assert!(c.apply(t0, None, Some(bad)).is_err());
        assert_eq!(c.stamps(t0).unwrap().1.month, 11);
    }

    #[test]
    fn fields_not_sent_keep_their_value() {
        let t0 = Instant::now();
        let mut c = Clock::default();
        // A time alone on a clock never set: 1970-01 with the day of the time stamp.
        let time = TimeOfDay {
            hour: 12,
            day: 3,
            ..TimeOfDay::default()
        };
        c.apply(t0, Some(time), None).unwrap();
        assert_eq!(c.utc(t0), Some(Duration::from_secs((2 * 24 + 12) * 3600)));
        // A date alone keeps the time of day.
        let date = Date {
            day: 1,
            month: 1,
            year: 0,
        };
        c.apply(t0, None, Some(date)).unwrap();
        let (t, d) = c.stamps(t0).unwrap();
        assert_eq!((t.hour, t.day, d.year, d.month), (12, 1, 0, 1));
    }

    #[test]
    fn ra33_stamps_round_trip() {
        let t0 = Instant::now();
        let mut c = Clock::default();
        let date = DateStamp {
            day: 22,
            month: 11,
            year: 26,
            reserved: 0,
        };
        let time = TimeStamp {
            millisecond: 250,
            second: 7,
            minute: 6,
            hour: 3,
            day: 22,
            reserved: 0,
        };
        assert!(c
            .apply(t0, Some((&time).into()), Some((&date).into()))
            .is_ok());
        let (ts, ds) = ra33(c.stamps(t0 + Duration::from_millis(1_000))).unwrap();
        assert_eq!(
            (ts.hour, ts.minute, ts.second, ts.millisecond, ts.day),
            (3, 6, 8, 250, 22)
        );
        assert_eq!((ds.year, ds.month, ds.day), (26, 11, 22));
        assert_eq!(ra33(c.stamps(t0)).unwrap(), (time, date));
    }
}
