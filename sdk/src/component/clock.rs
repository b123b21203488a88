//! A component's UTC clock: set from the shell (or by Set Time), read for Report Time.
//! No wall clock is read here; the time of day is derived from the `now` the runtime is
//! given, so virtual-clock tests are deterministic.

use std::time::{Duration, Instant};

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
        let current = self.utc(now).unwrap_or_default();
        let days = (current.as_secs() / 86_400) as i64;
        let (mut y, mut m, mut d) = civil_from_days(days);
        let mut tod_ms = (current.as_millis() % 86_400_000) as u64;
        if let Some(ds) = date {
            y = 2000 + i64::from(ds.year);
            m = u32::from(ds.month);
            d = u32::from(ds.day);
        }
        if let Some(ts) = time {
            if ts.hour > 23 || ts.minute > 59 || ts.second > 59 || ts.millisecond > 999 {
                return false;
            }
            d = u32::from(ts.day);
            tod_ms = ((u64::from(ts.hour) * 60 + u64::from(ts.minute)) * 60 + u64::from(ts.second))
                * 1000
                + u64::from(ts.millisecond);
        }
        if !(1..=12).contains(&m) || d == 0 || d > days_in_month(y, m) {
            return false;
        }
        let days = days_from_civil(y, m, d);
        if days < 0 {
            return false;
        }
        let ms = days as u64 * 86_400_000 + tod_ms;
        self.set(now, Duration::from_millis(ms));
        true
    }

    pub(crate) fn stamps(&self, now: Instant) -> Option<(TimeStamp, DateStamp)> {
        let utc = self.utc(now)?;
        let ms_total = utc.as_millis();
        let days = (utc.as_secs() / 86_400) as i64;
        let (y, m, d) = civil_from_days(days);
        let tod = (ms_total % 86_400_000) as u64;
        let time = TimeStamp {
            millisecond: (tod % 1000) as u16,
            second: (tod / 1000 % 60) as u8,
            minute: (tod / 60_000 % 60) as u8,
            hour: (tod / 3_600_000) as u8,
            day: d as u8,
            reserved: 0,
        };
        let date = DateStamp {
            day: d as u8,
            month: m as u8,
            year: (y - 2000).clamp(0, 127) as u8,
            reserved: 0,
        };
        Some((time, date))
    }
}

fn is_leap(y: i64) -> bool {
    (y % 4 == 0 && y % 100 != 0) || y % 400 == 0
}

fn days_in_month(y: i64, m: u32) -> u32 {
    match m {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        _ if is_leap(y) => 29,
        _ => 28,
    }
}

/// Days since 1970-01-01 of a proleptic Gregorian date (the "days from civil"
/// algorithm: shift the year to start in March so the leap day is last).
fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (i64::from(m) + 9) % 12;
    let doy = (153 * mp + 2) / 5 + i64::from(d) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The inverse of [`days_from_civil`].
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calendar_conversion_matches_known_dates() {
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(2000, 3, 1), 11_017);
        // 2026-11-22 is 20,779 days after the epoch.
        assert_eq!(days_from_civil(2026, 11, 22), 20_779);
        for z in [0, 59, 60, 11_016, 11_017, 20_779, 47_541] {
            let (y, m, d) = civil_from_days(z);
            assert_eq!(days_from_civil(y, m, d), z);
        }
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
        assert_eq!(civil_from_days(47_541), (2100, 3, 1));
    }

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
