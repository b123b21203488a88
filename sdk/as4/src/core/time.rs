//! Time (`urn:jaus:jss:core:Time` 1.1): the component's UTC clock.
//!
//! The runtime reads no clock: the owner tells the component the wall-clock time once
//! ([`Time::set_utc`]: UTC since 1970-01-01 at an `Instant`), and the clock runs on with
//! the `now` of each call. Set Time (from the controlling client) moves it: the time
//! stamp sets the day of the month and the time of day, the date stamp the date;
//! fields not sent keep their value. Until the clock is known, Report Time carries
//! neither field (both are optional).

use std::time::{Duration, Instant};

use crate::messages::{DateStamp, QueryTime, ReportTime, SetTime, TimeStamp};

const DAY_MS: u64 = 86_400_000;

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
        let ms = u64::try_from(self.utc(now)?.as_millis()).ok()?;
        let (y, m, d) = civil_from_days((ms / DAY_MS) as i64);
        let tod = ms % DAY_MS;
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
        let current = self
            .utc(now)
            .map_or(0, |u| u64::try_from(u.as_millis()).unwrap_or(0));
        let (mut y, mut m, mut d) = civil_from_days((current / DAY_MS) as i64);
        let mut tod = current % DAY_MS;
        if let Some(ds) = &msg.date_stamp {
            (y, m, d) = (
                2000 + i64::from(ds.year),
                u32::from(ds.month),
                u32::from(ds.day),
            );
        }
        if let Some(ts) = &msg.time_stamp {
            if ts.hour > 23 || ts.minute > 59 || ts.second > 59 || ts.millisecond > 999 {
                return Err(format!(
                    "impossible time {:02}:{:02}:{:02}.{:03}",
                    ts.hour, ts.minute, ts.second, ts.millisecond
                ));
            }
            d = u32::from(ts.day);
            tod = ((u64::from(ts.hour) * 60 + u64::from(ts.minute)) * 60 + u64::from(ts.second))
                * 1000
                + u64::from(ts.millisecond);
        }
        if !(1..=12).contains(&m) || d == 0 || d > days_in_month(y, m) {
            return Err(format!("impossible date {y}-{m:02}-{d:02}"));
        }
        let days = days_from_civil(y, m, d);
        let ms = u64::try_from(days).map_err(|_| "date before 1970".to_string())? * DAY_MS + tod;
        self.set_utc(now, Duration::from_millis(ms));
        Ok(())
    }
}

fn is_leap(y: i64) -> bool {
    y % 4 == 0 && (y % 100 != 0 || y % 400 == 0)
}

fn days_in_month(y: i64, m: u32) -> u32 {
    const DAYS: [u32; 12] = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    if m == 2 && is_leap(y) {
        29
    } else {
        DAYS[(m.clamp(1, 12) - 1) as usize]
    }
}

/// Days since 1970-01-01 of a Gregorian date. Counts from 1 March of year 0 so that
/// the leap day falls at the end of each counted year, in 400-year cycles.
fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let (y, m) = if m <= 2 {
        (y - 1, i64::from(m) + 9)
    } else {
        (y, i64::from(m) - 3)
    };
    let cycle = y.div_euclid(400);
    let year_of_cycle = y - cycle * 400;
    let day_of_year = (153 * m + 2) / 5 + i64::from(d) - 1;
    let day_of_cycle = year_of_cycle * 365 + year_of_cycle / 4 - year_of_cycle / 100 + day_of_year;
    cycle * 146_097 + day_of_cycle - 719_468
}

/// The date of a day count since 1970-01-01 (inverse of [`days_from_civil`]).
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let cycle = z.div_euclid(146_097);
    let day_of_cycle = z - cycle * 146_097;
    let year_of_cycle =
        (day_of_cycle - day_of_cycle / 1460 + day_of_cycle / 36_524 - day_of_cycle / 146_096) / 365;
    let day_of_year =
        day_of_cycle - (365 * year_of_cycle + year_of_cycle / 4 - year_of_cycle / 100);
    let mp = (5 * day_of_year + 2) / 153;
    let d = (day_of_year - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (year_of_cycle + cycle * 400 + i64::from(m <= 2), m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calendar_round_trip() {
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(2000, 3, 1), 11_017);
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
        for z in [0, 59, 60, 11_016, 20_779, 47_541] {
            let (y, m, d) = civil_from_days(z);
            assert_eq!(days_from_civil(y, m, d), z);
        }
    }
}
