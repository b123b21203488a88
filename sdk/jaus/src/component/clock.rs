//! A component's UTC clock: set from the shell (or by Set Time), read for Report Time.
//! No wall clock is read here; the time of day is derived from the `now` the runtime is
//! given, so virtual-clock tests are deterministic.

use std::time::{Duration, Instant};

use crate::calendar::Civil;
use crate::messages::{DateStamp, TimeStamp};

/// UTC as a duration since 1970-01-01T00:00:00Z, anchored to a runtime instant.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Clock {
    anchor: Option<(Instant, Duration)>,
}

impl Clock {
    pub(crate) fn set(&mut self, at: Instant, utc: Duration) {
        self.anchor = Some((at, utc));
    }

    pub(crate) fn utc(&self, now: Instant) -> Option<Duration> {
        self.anchor
            .map(|(at, utc)| utc + now.saturating_duration_since(at))
    }

    /// Applies a Set Time: the time stamp replaces the day of month and the time of day,
    /// the date stamp the calendar date. Fields not sent keep their current value (or
    /// 1970-01-01 / midnight when the clock was never set). Returns false for an
    /// impossible date or time (nothing is changed then).
    pub(crate) fn apply(
        &mut self,
        now: Instant,
        time: Option<&TimeStamp>,
        date: Option<&DateStamp>,
    ) -> bool {
        let mut c = Civil::from_utc(self.utc(now).unwrap_or_default());
        if let Some(ds) = date {
            c.year = 2000 + i64::from(ds.year);
            c.month = u32::from(ds.month);
            c.day = u32::from(ds.day);
        }
        if let Some(ts) = time {
            c.day = u32::from(ts.day);
            c.hour = u32::from(ts.hour);
            c.minute = u32::from(ts.minute);
            c.second = u32::from(ts.second);
            c.millisecond = u32::from(ts.millisecond);
        }
        match c.to_utc() {
            Ok(utc) => {
                self.set(now, utc);
                true
            }
            Err(_) => false,
        }
    }

    pub(crate) fn stamps(&self, now: Instant) -> Option<(TimeStamp, DateStamp)> {
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_time_then_read_stamps() {
        let t0 = Instant::now();
        let mut c = Clock::default();
        assert!(c.stamps(t0).is_none());
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
        assert!(c.apply(t0, Some(&time), Some(&date)));
        let (ts, ds) = c.stamps(t0 + Duration::from_millis(1_000)).unwrap();
        assert_eq!(
            (ts.hour, ts.minute, ts.second, ts.millisecond, ts.day),
            (3, 6, 8, 250, 22)
        );
        assert_eq!((ds.year, ds.month, ds.day), (26, 11, 22));
        // An impossible date changes nothing.
        let bad = DateStamp {
            day: 31,
            month: 2,
            year: 26,
            reserved: 0,
        };
        assert!(!c.apply(t0, None, Some(&bad)));
        assert_eq!(c.stamps(t0).unwrap().1.month, 11);
    }
}
